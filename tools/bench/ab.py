#!/usr/bin/python3
"""Before/after comparison of two commands, run interleaved on this machine.

usage: tools/bench/ab.py [-n ROUNDS] [--label-a NAME] [--label-b NAME] [--env-a K=V] [--env-b K=V]
                         -- COMMAND_A ... ::: COMMAND_B ...

Runs the two commands ROUNDS times each, interleaved A B, B A, A B, ... (so neither always runs first
after the other), and prints for each: the wall time, the user and system CPU time and the peak RSS
(the child's ru_maxrss, i.e. its VmHWM, or this script's own size if that is larger), as medians with their ranges; then the median of the
differences B - A within each round and in how many rounds B was faster. A command that fails stops the
comparison (exit code 1, its stderr shown).

Why: the host's speed drifts from minute to minute, so only runs interleaved with each other
compare, and one pair says little; the system time apart shows what page faults and pages given back
cost (docs/benchmarks.md). Example (the previous build's program against this one):

  tools/bench/ab.py -n 6 -- /tmp/base/build/bin/fdrmesh mesh R.gpkg --layer water --raster R.tif \\
      --hmin 120 -q -o /tmp/a.2dm ::: build/bin/fdrmesh mesh R.gpkg --layer water --raster R.tif \\
      --hmin 120 -q -o /tmp/b.2dm
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time


def run_once(cmd, env):
    """Runs cmd; returns (wall s, user s, system s, peak MiB) or raises RuntimeError."""
    # stderr to a file, not a pipe: a chatty command cannot block on a full pipe while we wait.
    with tempfile.TemporaryFile() as errf:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=errf, env=env)
        # wait4 gives this child's own resource usage (not the sum over every child so far).
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            errf.seek(0)
            err = errf.read().decode(errors="replace")
            raise RuntimeError(f"{' '.join(cmd)} exited with {proc.returncode}:\n{err}")
    return wall, ru.ru_utime, ru.ru_stime, ru.ru_maxrss / 1024.0


def summary(values, fmt):
    return f"{fmt % statistics.median(values)} ({fmt % min(values)}-{fmt % max(values)})"


def parse_env(pairs):
    env = dict(os.environ)
    for p in pairs or []:
        if "=" not in p:
            raise SystemExit(f"ab.py: --env-a/--env-b take K=V, got '{p}'")
        k, v = p.split("=", 1)
        env[k] = v
    return env


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 usage="%(prog)s [options] -- COMMAND_A ... ::: COMMAND_B ...")
    ap.add_argument("-n", "--rounds", type=int, default=5, help="runs of each command (default 5)")
    ap.add_argument("--label-a", default="A")
    ap.add_argument("--label-b", default="B")
    ap.add_argument("--env-a", action="append", help="K=V set for command A only (repeatable)")
    ap.add_argument("--env-b", action="append", help="K=V set for command B only (repeatable)")
    ap.add_argument("commands", nargs=argparse.REMAINDER)
    a = ap.parse_args(argv)
    words = a.commands[1:] if a.commands[:1] == ["--"] else a.commands
    if ":::" not in words:
        ap.error("give two commands: -- COMMAND_A ... ::: COMMAND_B ...")
    k = words.index(":::")
    cmds = {a.label_a: words[:k], a.label_b: words[k + 1:]}
    if not cmds[a.label_a] or not cmds[a.label_b]:
        ap.error("each command needs at least a program")
    if not 1 <= a.rounds <= 1000:
        ap.error("--rounds must be between 1 and 1000")
    if a.label_a == a.label_b:
        ap.error("the two labels must differ")
    envs = {a.label_a: parse_env(a.env_a), a.label_b: parse_env(a.env_b)}
    results = {a.label_a: [], a.label_b: []}
    for r in range(a.rounds):
        order = [a.label_a, a.label_b] if r % 2 == 0 else [a.label_b, a.label_a]
        for lab in order:
            try:
                results[lab].append(run_once(cmds[lab], envs[lab]))
            except (RuntimeError, OSError) as e:
                print(f"ab.py: {e}", file=sys.stderr)
                return 1
        print(f"round {r + 1}/{a.rounds}: " +
              ", ".join(f"{lab} {results[lab][-1][0]:.3f} s" for lab in (a.label_a, a.label_b)),
              file=sys.stderr, flush=True)
    # A child's ru_maxrss also counts the memory of this process it was forked from (Linux keeps the
    # larger of the two at exec): a peak at this floor means "this size or less".
    floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"{a.rounds} interleaved rounds (medians, ranges in brackets; peaks of {floor:.1f} MiB or less read as "
          f"{floor:.1f}: this script's own size)")
    width = max(len(a.label_a), len(a.label_b))
    for lab in (a.label_a, a.label_b):
        rs = results[lab]
        print(f"  {lab:<{width}}  wall {summary([x[0] for x in rs], '%.3f')} s"
              f"  user {summary([x[1] for x in rs], '%.3f')} s"
              f"  system {summary([x[2] for x in rs], '%.3f')} s"
              f"  peak {summary([x[3] for x in rs], '%.1f')} MiB")
    diffs = [b[0] - x[0] for x, b in zip(results[a.label_a], results[a.label_b])]
    faster = sum(1 for d in diffs if d < 0)
    print(f"  {a.label_b} - {a.label_a} per round: wall median {statistics.median(diffs):+.3f} s "
          f"(range {min(diffs):+.3f} to {max(diffs):+.3f}); {a.label_b} faster in {faster} of {a.rounds} rounds")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
