#!/usr/bin/python3
"""A fake V&V case for test_shard_script.py: writes a synthetic record for CASE into
$ERYTHRO_RESULTS_DIR, as a C++ case would, and exits 0."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import synthetic  # noqa: E402

case = sys.argv[1]
synthetic.write_record(os.path.join(os.environ["ERYTHRO_RESULTS_DIR"], f"{case}.h5"), case,
                       metrics=[synthetic.metric("m", 1.0, 1.0, 0.1)])
