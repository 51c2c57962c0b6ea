"""erythro V&V report generator: reads result records, writes HTML and Markdown.

Modules, one job each:
  h5text     decoding HDF5 strings and numbers (fixed/variable length, bytes/str)
  records    reading one result record (schema: solver/io/result_record.hpp)
  expected   the list of expected cases (expected_cases.tsv) and label filters
  model      gathering records into a report: sorting, checks, problems
  formatting numbers, tolerances and the cheapest set-up, as text
  plots      matplotlib figures (Agg), saved as PNG files
  html_report / markdown_report   the two outputs
  cli        the command line (reports/generate.py calls cli.main)
  doc_sections / doc_markdown / doc_tables_cli   the measured sections of the docs pages
             (reports/doc_tables.py calls doc_tables_cli.main)
"""
