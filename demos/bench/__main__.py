"""``python -m demos.bench [TOPIC ...] [--quick]``: run the benchmarks and print their tables."""

from __future__ import annotations

import argparse
import importlib
import inspect
import sys
from pathlib import Path

from demos.bench import TOPICS


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m demos.bench",
        description="Speed measured side by side in one run, reported as ratios.",
    )
    parser.add_argument(
        "topics",
        nargs="*",
        metavar="TOPIC",
        help=f"which to run (default all): {', '.join(TOPICS)}",
    )
    parser.add_argument("--quick", action="store_true", help="fewer, shorter rounds")
    parser.add_argument(
        "--out",
        type=Path,
        default=Path("out") / "bench",
        help="folder for the pictures a topic draws (default out/bench; same names replaced)",
    )
    args = parser.parse_args(argv)
    unknown = [t for t in args.topics if t not in TOPICS]
    if unknown:
        parser.error(f"unknown topic {unknown[0]!r}; valid topics: {', '.join(TOPICS)}")
    for topic in args.topics or list(TOPICS):
        try:
            module = importlib.import_module(TOPICS[topic])
        except ModuleNotFoundError as error:
            print(f"{topic}: not available ({error})", file=sys.stderr)
            continue
        takes_out = "out" in inspect.signature(module.report).parameters
        extra = {"out": args.out} if takes_out else {}
        print(module.report(quick=args.quick, **extra), flush=True)
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
