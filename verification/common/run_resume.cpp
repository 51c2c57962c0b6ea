#include "common/run_resume.hpp"

#include <exception>
#include <filesystem>

#include "common/build_info.hpp"
#include "simulation/run_observer.hpp"

namespace erythro::vv {
namespace fs = std::filesystem;

bool revision_can_resume(const std::string& rev) {
  const std::string dirty = "-dirty";
  return !rev.empty() && rev != "unknown" &&
         !(rev.size() >= dirty.size() && rev.compare(rev.size() - dirty.size(), dirty.size(), dirty) == 0);
}

bool build_can_resume() { return revision_can_resume(build_info::git_revision()); }

ResumePoint find_resume_point(const std::string& dir, const std::string& scene_text) {
  ResumePoint point;
  if (!build_can_resume()) {
    point.note = "this build (" + build_info::git_revision() + ") does not resume: its revision is not clean";
    return point;
  }
  if (!fs::is_directory(dir)) {
    point.note = "no earlier run";
    return point;
  }
  const std::string rev = build_info::git_revision();
  const fs::path finished = fs::path(dir) / "run.h5";
  if (fs::exists(finished)) {
    try {
      io::RunFile file(finished.string());
      const std::optional<sim::RunStatus> status = sim::run_status_from(file.status());
      if (file.scene_text() == scene_text && file.git_revision() == rev && status &&
          *status != sim::RunStatus::interrupted) {
        point.note = "read back the finished run " + finished.string();
        point.finished = std::move(file);
        return point;
      }
    } catch (const std::exception&) {
      // unreadable: not finished; a checkpoint may still hold the run
    }
  }
  try {
    io::Checkpoint c = io::read_checkpoint(dir);
    if (c.scene_text == scene_text && c.git_revision == rev) {
      point.note = "continued from step " + std::to_string(c.step) + " of " + c.path;
      point.checkpoint = std::move(c);
      return point;
    }
    point.note = "the checkpoint in " + dir + " is of another scene or build: started afresh";
  } catch (const std::exception&) {
    point.note = "no complete checkpoint in " + dir + ": started afresh";
  }
  return point;
}

}  // namespace erythro::vv
