"""``dustygas problems``: list registered problems, or show one problem's parameters."""

from __future__ import annotations

import argparse

HELP = "list registered problems, or show the parameters of one"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("name", nargs="?", help="show this problem's parameters with defaults and units")


def main(args: argparse.Namespace) -> int:
    from ..config import describe_schema
    from ..problems import all_problems, get_problem

    if args.name:
        prob = get_problem(args.name)
        print(f"{prob.name}: {prob.summary}\n")
        print(describe_schema(prob.schema))
        return 0
    problems = all_problems()
    width = max((len(n) for n in problems), default=0)
    for name, prob in problems.items():
        print(f"{name:<{width}}  {prob.summary}")
    return 0
