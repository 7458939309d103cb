"""Tests of tools/bench/ab.py (the interleaved before/after comparison)."""
import os
import subprocess
import sys

AB = os.path.join(os.path.dirname(os.path.abspath(__file__)), "ab.py")
PY = sys.executable


def ab(*args):
    return subprocess.run([PY, AB, *args], capture_output=True, text=True, timeout=120)


def test_slower_command_and_its_peak_are_measured():
    # B sleeps 0.2 s and touches 256 MiB; A does neither.
    touch = "import time; b = bytearray(256 << 20); b[::4096] = b'x' * len(b[::4096]); time.sleep(0.2)"
    r = ab("-n", "3", "--label-a", "quick", "--label-b", "slow", "--", PY, "-c", "pass", ":::", PY, "-c", touch)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].startswith("3 interleaved rounds")
    slow = next(l for l in lines if l.strip().startswith("slow "))
    peak = float(slow.split("peak ")[1].split()[0])
    assert peak >= 256, slow
    wall = float(slow.split("wall ")[1].split()[0])
    assert wall >= 0.2, slow
    assert "slow faster in 0 of 3 rounds" in lines[-1]
    # Interleaved: the rounds alternate which command runs first.
    assert r.stderr.count("round ") == 3


def test_environment_per_command():
    check = "import os, sys; sys.exit(0 if os.environ.get('AB_T') == 'b' else 3)"
    r = ab("-n", "1", "--env-b", "AB_T=b", "--", PY, "-c", "pass", ":::", PY, "-c", check)
    assert r.returncode == 0, r.stderr
    r = ab("-n", "1", "--env-a", "AB_T=b", "--", PY, "-c", "pass", ":::", PY, "-c", check)
    assert r.returncode == 1
    assert "exited with 3" in r.stderr


def test_failing_command_stops_with_its_stderr():
    r = ab("-n", "2", "--", PY, "-c", "import sys; sys.stderr.write('boom'); sys.exit(2)", ":::", PY, "-c", "pass")
    assert r.returncode == 1
    assert "exited with 2" in r.stderr and "boom" in r.stderr


def test_usage_errors():
    assert ab("--", "true").returncode == 2
    assert ab("-n", "0", "--", "true", ":::", "true").returncode == 2
    assert ab("--label-a", "x", "--label-b", "x", "--", "true", ":::", "true").returncode == 2
