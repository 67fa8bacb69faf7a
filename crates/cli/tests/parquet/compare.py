"""Compare Parquet files with the CSV files of the same tables, column by column (issue 21).

Usage: python3 compare.py CSV PARQUET [CSV PARQUET ...]
For each pair: the same column names in the same order, the same number of rows, a typed
column (float64, int64, uint64, string or bool; never text for a numeric CSV column), and
every cell equal: an empty CSV cell is a null, numbers are equal as numbers (the CSV's
shortest round-trip text parses back to the same float64), words and flags are equal as text.
Prints one line per pair; exits 1 at the first difference.
"""

import csv
import sys

import pyarrow as pa
import pyarrow.parquet as pq


def compare(csv_path, parquet_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    table = pq.read_table(parquet_path)
    if table.column_names != header:
        raise AssertionError(f"{parquet_path}: columns {table.column_names} != {header}")
    if table.num_rows != len(body):
        raise AssertionError(f"{parquet_path}: {table.num_rows} rows != {len(body)}")
    types = {}
    for c, name in enumerate(header):
        column = table.column(name)
        t = column.type
        values = column.to_pylist()
        if pa.types.is_floating(t):
            kind = "float64"
            same = lambda text, v: float(text) == v
        elif pa.types.is_integer(t):
            kind = str(t)
            same = lambda text, v: int(text) == v
        elif pa.types.is_boolean(t):
            kind = "bool"
            same = lambda text, v: text == ("true" if v else "false")
        elif pa.types.is_string(t) or pa.types.is_large_string(t):
            kind = "string"
            same = lambda text, v: text == v
            numeric = [r[c] for r in body if r[c] != ""]
            if numeric and all(is_number(x) for x in numeric) and name not in ("lane", "key"):
                raise AssertionError(f"{parquet_path}: numeric column {name} stored as text")
        else:
            raise AssertionError(f"{parquet_path}: column {name} has type {t}")
        types[kind] = types.get(kind, 0) + 1
        for i, (row, v) in enumerate(zip(body, values)):
            text = row[c]
            if v is None:
                ok = text == ""
            else:
                ok = text != "" and same(text, v)
            if not ok:
                raise AssertionError(
                    f"{parquet_path}: column {name}, row {i + 2}: CSV {text!r} vs Parquet {v!r}"
                )
    kinds = ", ".join(f"{n} {k}" for k, n in sorted(types.items()))
    print(f"{parquet_path}: {len(header)} columns x {len(body)} rows equal ({kinds})")


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def main():
    args = sys.argv[1:]
    for i in range(0, len(args), 2):
        compare(args[i], args[i + 1])


if __name__ == "__main__":
    main()
