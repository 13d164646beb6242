"""Every row of a CSV file has the header's number of fields, read as RFC 4180 (Python's csv).
Usage: check_csv_columns.py FILE COLUMN TEXT -- and the first data row's COLUMN equals TEXT."""
import csv
import sys

path, column, expected = sys.argv[1], sys.argv[2], sys.argv[3]
with open(path, newline="") as f:
    rows = list(csv.reader(f))
header = rows[0]
widths = {len(r) for r in rows}
if widths != {len(header)}:
    sys.exit(f"{path}: rows of {sorted(widths)} fields, header has {len(header)}")
value = rows[1][header.index(column)]
if value != expected:
    sys.exit(f"{path}: {column} reads {value!r}, expected {expected!r}")
print(f"{path}: {len(rows) - 1} rows of {len(header)} fields; {column} = {value!r}: ok")
