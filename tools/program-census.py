#!/usr/bin/env python3
"""Which tests compile which OpenCL programs (docs/testing.md, "Where a cold
suite's time goes").

A cold suite spends most of its time in PoCL compiling programs, a few
seconds for each distinct (source, options) pair. Run the suite with
WAVEPATH_PROGRAM_LOG set (src/cl/program.cpp appends one line per program
build asked for), then summarise the log:

    WAVEPATH_PROGRAM_LOG=/tmp/programs.log ctest --test-dir build -j2
    python3 tools/program-census.py /tmp/programs.log [--top 25]

The cache state does not matter: a warm run asks for the same programs as a
cold one. The table lists, per test case, the programs it asks for, how many
are distinct, and how many no other test asks for: those it alone pays for
when the caches are cold, and the ones a cheaper test would save.
"""
import argparse
import collections
import sys


def test_name(process: str) -> str:
    """The test case a logged process ran: ctest passes the Catch2 name as an
    argument after the executable; anything else is named by its command."""
    words = process.split(" ")
    executable = words[0].rsplit("/", 1)[-1]
    names = [w for w in words[1:] if w and not w.startswith("-") and w != "NoTests"]
    return f"{executable}: {' '.join(names)}" if names else executable


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("log", help="the file WAVEPATH_PROGRAM_LOG named")
    parser.add_argument("--top", type=int, default=25, help="rows of the table (default 25)")
    args = parser.parse_args()

    asked = collections.Counter()
    programs_of = collections.defaultdict(set)
    tests_of = collections.defaultdict(set)
    sources = {}
    with open(args.log, encoding="utf-8", errors="replace") as log:
        for line in log:
            parts = line.rstrip("\n").split("\t", 3)
            if len(parts) != 4:
                continue
            program, source, _options, process = parts
            test = test_name(process)
            asked[test] += 1
            programs_of[test].add(program)
            tests_of[program].add(test)
            sources[program] = source
    if not asked:
        print(f"program-census: no program builds in {args.log}", file=sys.stderr)
        return 1

    own = {t: sum(1 for p in ps if len(tests_of[p]) == 1) for t, ps in programs_of.items()}
    by_source = collections.Counter(sources.values())
    print(f"program-census: {sum(asked.values())} builds asked for by {len(asked)} processes; "
          f"{len(tests_of)} distinct programs ("
          + ", ".join(f"{n} {s}" for s, n in by_source.most_common()) + ")")
    shared = sum(1 for ts in tests_of.values() if len(ts) > 1)
    print(f"program-census: {shared} programs are asked for by more than one test, "
          f"{len(tests_of) - shared} by one test alone")
    print(f"{'own':>4} {'distinct':>8} {'asked':>6}  test (by programs no other test asks for)")
    rows = sorted(asked, key=lambda t: (-own[t], -len(programs_of[t]), t))
    try:
        for test in rows[: args.top]:
            print(f"{own[test]:4d} {len(programs_of[test]):8d} {asked[test]:6d}  {test[:110]}")
    except BrokenPipeError:  # a pager or head that has read enough
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
