#!/usr/bin/env python3
"""structmd's and UAMMD's rows of the hydrodynamics benchmark side by side (issue 33): steps/s, the
ratio structmd / UAMMD (the target is at least 1.5 at 10,000 and 100,000 particles), and each engine's
relative error of dt M F against its own reference (README.md says which).

usage: compare.py UAMMD_CSV [STRUCTMD_CSV]   (a missing structmd file leaves its columns empty)"""
import csv
import os
import sys


def rows(path):
    if not path or not os.path.exists(path):
        return {}
    with open(path, newline="") as f:
        return {(r["method"], int(r["n"])): r for r in csv.DictReader(f)}


def number(text):
    return float(text) if text not in ("", None) else None


def shown(value, form):
    return "-" if value is None else format(value, form)


def main():
    uammd = rows(sys.argv[1])
    structmd = rows(sys.argv[2] if len(sys.argv) > 2 else None)
    print("| method | N | tolerance | UAMMD steps/s | structmd steps/s | structmd / UAMMD | UAMMD error | structmd error |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for key, u in uammd.items():
        s = structmd.get(key, {})
        u_rate, s_rate = number(u["steps_per_second"]), number(s.get("steps_per_second"))
        ratio = s_rate / u_rate if u_rate and s_rate else None
        print(f"| {key[0]} | {key[1]:,} | {u['tolerance'] or 'exact'} | {shown(u_rate, ',.0f')} | {shown(s_rate, ',.0f')} "
              f"| {shown(ratio, '.2f')} | {shown(number(u['error']), '.1e')} | {shown(number(s.get('error')), '.1e')} |")


if __name__ == "__main__":
    main()
