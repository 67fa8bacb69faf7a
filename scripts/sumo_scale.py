#!/usr/bin/env python3
"""Synthetic SUMO networks for the importer's scaling benchmark (docs/import.md, "Scaling").

Writes a `.net.xml` of a given shape and size to stdout or --out (standard library only):

  chain N      a motorway of N edges in a row, 2 lanes each, 1 m long (N edges, 2N lanes,
               2N connections: the mainline the importer follows, end to end)
  conns N      a motorway of N/16 edges of 4 lanes, 3 m long, each lane connected to all
               four lanes of the next edge (N connections)
  deep N       one element nested N levels deep (the stack-overflow case)

Each element is one line, as netconvert writes them. Time an import with
`platoonsim import sumo FILE --out /tmp/x.toml` under `/usr/bin/time -v` (wall time, peak RSS).
"""

import argparse
import sys


def chain(n, lanes, length, fanout, out):
    w = out.write
    w('<net version="1.20">\n')
    for k in range(n):
        w(f'  <edge id="e{k}" from="n{k}" to="n{k + 1}" type="highway.motorway">\n')
        for i in range(lanes):
            w(f'    <lane id="e{k}_{i}" index="{i}" speed="33.33" length="{length}"/>\n')
        w("  </edge>\n")
    for k in range(n - 1):
        for i in range(lanes):
            targets = range(lanes) if fanout else [i]
            for j in targets:
                w(f'  <connection from="e{k}" to="e{k + 1}" fromLane="{i}" toLane="{j}" dir="s"/>\n')
    w("</net>\n")


def deep(n, out):
    out.write('<net version="1.20">\n' + "<a>" * n + "</a>" * n + "\n</net>\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("shape", choices=["chain", "conns", "deep"])
    p.add_argument("n", type=int)
    p.add_argument("--out", help="file to write (default: stdout)")
    a = p.parse_args()
    out = open(a.out, "w") if a.out else sys.stdout
    if a.shape == "chain":
        chain(a.n, 2, 1, False, out)
    elif a.shape == "conns":
        chain(max(2, a.n // 16 + 1), 4, 3, True, out)
    else:
        deep(a.n, out)
    out.close()


if __name__ == "__main__":
    main()
