#!/usr/bin/env python3
"""Writes the option tables of docs/user-guide.md from src/api/option_table.cpp, and the table of
the report's keys from src/report/run_report.cpp: each table between its markers is replaced by
`neomesh smooth --help-markdown` (`adapt`), the report's by `neomesh smooth --report-markdown`.
The unit tests OptionDocs.TheUserGuideShowsTheTablesOfSmoothAndAdapt and
ReportDocs.TheUserGuideShowsTheTableOfTheReportsKeys fail until this is run after a change of a
table.

usage: scripts/update_option_docs.py NEOMESH [SOURCE_DIR]"""
import os
import re
import subprocess
import sys


def main():
    neomesh = sys.argv[1]
    source = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "..")
    guide = os.path.join(source, "docs", "user-guide.md")
    with open(guide, encoding="utf-8") as f:
        text = f.read()
    tables = [(["smooth", "--help-markdown"], "options of smooth"),
              (["adapt", "--help-markdown"], "options of adapt"),
              (["smooth", "--report-markdown"], "keys of the report")]
    for arguments, what in tables:
        table = subprocess.run([neomesh] + arguments, check=True, capture_output=True,
                               text=True).stdout
        pattern = re.compile(rf"(<!-- {what}: generated[^\n]*\n).*?(<!-- end of the {what} -->)",
                             re.S)
        text, count = pattern.subn(lambda m: m.group(1) + table + m.group(2), text)
        if count != 1:
            sys.exit(f"{guide}: no markers of the {what}")
    with open(guide, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main()
