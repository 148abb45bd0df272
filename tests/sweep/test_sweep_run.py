# SPDX-License-Identifier: BSD-3-Clause
"""gencoord sweep end to end under MPI: a small double-pendulum sweep gives byte-identical
results (datasets, and whole files) with 1, 2 and 4 ranks (4 oversubscribed) and 1 or 2
threads; a run killed midway resumes from its completed chunks without running them again
and ends with the bytes of an uninterrupted run; samples whose dynamics fail are recorded and
the run goes on; a rank that dies is reported; a closed loop (the four-bar) starts each sample
on its constraint and ends on it; a free trunk with a ball-jointed arm (unit quaternions,
generalized speeds) starts each sample with its quaternions normalized and keeps them unit.
Needs mpirun, the sweep program's MPI and HDF5, and h5py for $GENCOORD_H5PY_PYTHON (default
/usr/bin/python3), which reads the results (tests/sweep/h5_digest.py)."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
GENCOORD = REPOSITORY / "gencoord"
DIGEST = REPOSITORY / "tests" / "sweep" / "h5_digest.py"
H5PY_PYTHON = os.environ.get("GENCOORD_H5PY_PYTHON", "/usr/bin/python3")
MODEL = REPOSITORY / "models" / "double_pendulum.py"


def sweep_file(points: int, t_end: float, chunk: int) -> str:
    """Time to flip of the double pendulum on a grid of initial angles."""
    return f"""\
[model]
file = "{MODEL}"

[integration]
integrator = "rk4"
dt = 0.01
t_end = {t_end}

[event]
when = "abs(theta1) > pi or abs(theta2) > pi"

[samples]
method = "grid"
chunk = {chunk}

[samples.q]
theta1 = {{ from = "-pi", to = "pi", points = {points} }}
theta2 = {{ from = "-pi", to = "pi", points = {points} }}

[record]
trajectory_every = 500
"""


SMALL = sweep_file(points=20, t_end=20.0, chunk=8)      # 400 samples, 50 chunks
LONGER = sweep_file(points=72, t_end=60.0, chunk=16)    # 5184 samples, 324 chunks

# samples whose mass matrix is singular (a massless bob) or whose forces overflow (g = 1e300)
FAILING = f"""\
[model]
file = "{MODEL}"

[integration]
dt = 0.01
t_end = 1.0

[samples]
method = "grid"

[samples.q]
theta1 = {{ values = [0.5] }}

[samples.parameters]
m2 = {{ values = [1.0, 0.0] }}
g = {{ values = [9.81, 1e300] }}
"""

# the four-bar, closed by a loop constraint, driven at a range of crank rates and torques
FOUR_BAR = f"""\
[model]
file = "{REPOSITORY / "models" / "four_bar.py"}"

[integration]
dt = 0.001
t_end = 5.0

[samples]
method = "grid"

[samples.v]
crank = {{ from = 0, to = 6, points = 4 }}

[samples.parameters]
u = {{ values = [0.0, 2.0] }}

[record]
final_state = true
"""


# a free trunk, a ball-jointed arm and a hand (tests/python_module/floating_arm.py: nq = 12,
# nv = 10): the table sets one component of the trunk's quaternion and its spin
FLOATING = f"""\
[model]
file = "{REPOSITORY / "tests" / "python_module" / "floating_arm.py"}"

[integration]
dt = 0.001
t_end = 1.0

[event]
when = "abs(arm_wz) > 100 or hand_joint_dot > 100"

[samples]
method = "grid"

[samples.q]
trunk_qx = {{ values = [0.0, 0.5] }}

[samples.v]
trunk_wz = {{ values = [0.0, 3.0] }}

[record]
trajectory_every = 250
"""


class SweepRunTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="gencoord-sweep-")
        cls.home = Path(cls.scratch.name)
        cache = os.environ.get("GENCOORD_TEST_CACHE_DIR") or str(cls.home / "cache")
        if os.environ.get("GENCOORD_TEST_CACHE_DIR"):
            shutil.rmtree(cache, ignore_errors=True)  # every run builds from nothing
        cls.environment = dict(os.environ, PYTHONHASHSEED="0", GENCOORD_CACHE_DIR=cache)
        for name, text in (("small", SMALL), ("longer", LONGER), ("failing", FAILING),
                           ("four_bar", FOUR_BAR), ("floating", FLOATING)):
            (cls.home / f"{name}.toml").write_text(text, encoding="utf-8")

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def gencoord(self, *arguments: str, folder: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, str(GENCOORD), "sweep", *arguments, "-o",
                               folder], cwd=self.home, env=self.environment,
                              capture_output=True, text=True, check=False, timeout=1800)

    def assertSucceeded(self, result):
        self.assertEqual(result.returncode, 0,
                         f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")
        self.assertNotIn("Traceback", result.stdout + result.stderr)

    def results(self, path: Path) -> dict:
        report = subprocess.run([H5PY_PYTHON, str(DIGEST), str(path)], capture_output=True,
                                text=True, check=True)
        return json.loads(report.stdout)

    def test_1_results_are_identical_with_any_ranks_and_threads(self):
        runs = {"1 rank": ("--ranks", "1", "--threads", "1"),
                "1 rank, 2 threads": ("--ranks", "1", "--threads", "2"),
                "2 ranks": ("--ranks", "2"),
                "4 ranks": ("--ranks", "4")}
        reports = {}
        for k, (label, options) in enumerate(runs.items()):
            result = self.gencoord("small.toml", *options, folder=f"run{k}")
            self.assertSucceeded(result)
            self.assertIn("400 samples of double_pendulum in 50 chunks of 8", result.stdout)
            # the preflight's estimate bounds the file: the data exactly, metadata up to 1 MiB
            estimate = re.search(r"gencoord: small: 400 samples x 2000 steps \(800,000 steps "
                                 r"in all\), results file about ([0-9.]+) MB", result.stdout)
            self.assertIsNotNone(estimate, result.stdout)
            size = (self.home / f"run{k}" / "small.h5").stat().st_size
            self.assertLess(size, float(estimate.group(1)) * 1.005e6)
            self.assertGreater(size, float(estimate.group(1)) * 0.995e6 - (1 << 20))
            self.assertIn("status      400 ok, 0 failed", result.stdout)
            reports[label] = self.results(self.home / f"run{k}" / "small.h5")
        reference = reports["1 rank"]
        self.assertEqual(reference["chunk_done"], [1] * 50)
        self.assertEqual(set(reference["status"]), {"ok"})
        self.assertEqual(reference["shapes"]["trajectory_q"], [400, 5, 2])
        self.assertEqual(reference["sweep"], SMALL)
        self.assertTrue(reference["banner"].startswith("// generated/double_pendulum.hpp"),
                        reference["banner"])
        self.assertIn("SymPy", reference["banner"])
        for label, report in reports.items():
            self.assertEqual(report["datasets"], reference["datasets"], label)
        # no clock times are stored, and the data is laid out in advance: the same bytes
        whole = {(self.home / f"run{k}" / "small.h5").read_bytes() for k in range(len(runs))}
        self.assertEqual(len(whole), 1)

    def test_2_a_killed_run_resumes_from_its_completed_chunks(self):
        # the reference: the same sweep in one go, on one rank
        self.assertSucceeded(self.gencoord("longer.toml", "--ranks", "1", folder="whole"))
        run = subprocess.Popen([sys.executable, str(GENCOORD), "sweep", "longer.toml",
                                "--ranks", "2", "-o", "killed"], cwd=self.home,
                               env=self.environment, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, start_new_session=True)
        seen = ""
        try:
            for line in run.stdout:  # progress lines: one per tenth of the samples
                seen += line
                done = re.search(r"sweep: (\d+) of 5184 samples", line)
                if done and int(done.group(1)) >= 1500:
                    break
        finally:
            os.killpg(run.pid, signal.SIGKILL)  # gencoord and mpirun; the ranks follow mpirun
            run.wait(timeout=60)
            run.stdout.close()
        self.assertNotIn("status ", seen, "the run ended before it was killed")
        self.wait_for_ranks_to_end(self.home / "killed" / "longer.table")
        partial = self.results(self.home / "killed" / "longer.h5")
        complete = sum(partial["chunk_done"])
        self.assertGreater(complete, 0, seen)
        self.assertLess(complete, 324, seen)

        resumed = self.gencoord("longer.toml", "--ranks", "2", "--resume", folder="killed")
        self.assertSucceeded(resumed)
        self.assertIn(f"holds {complete} of 324 chunks", resumed.stdout)
        self.assertIn(f"this run    {324 - complete} chunks", resumed.stdout)
        self.assertIn(f"{complete} chunks were complete before", resumed.stdout)
        final = self.results(self.home / "killed" / "longer.h5")
        self.assertEqual(final["datasets"], self.results(self.home / "whole" /
                                                         "longer.h5")["datasets"])
        self.assertEqual((self.home / "killed" / "longer.h5").read_bytes(),
                         (self.home / "whole" / "longer.h5").read_bytes())

        again = self.gencoord("longer.toml", "--resume", folder="killed")
        self.assertSucceeded(again)
        self.assertIn("nothing to do: every chunk was complete", again.stdout)
        refused = self.gencoord("longer.toml", folder="killed")
        self.assertEqual(refused.returncode, 1)
        self.assertIn("exists: --resume continues that sweep", refused.stderr)
        (self.home / "other.toml").write_text(LONGER.replace("t_end = 60.0", "t_end = 30.0"))
        shutil.copy(self.home / "killed" / "longer.h5", self.home / "killed" / "other.h5")
        mismatch = self.gencoord("other.toml", "--resume", folder="killed")
        self.assertEqual(mismatch.returncode, 1)
        self.assertIn("holds the results of another sweep", mismatch.stderr)
        self.assertNotIn("Traceback", mismatch.stderr)

    def wait_for_ranks_to_end(self, table: Path) -> None:
        """Waits until no process runs with `table` on its command line (the ranks end when
        mpirun is killed); kills any left after 30 s, which the test then reports."""
        deadline = time.monotonic() + 30
        while True:
            left = [pid for pid in os.listdir("/proc") if pid.isdigit()
                    and str(table).encode() in self.command_line(pid)]
            if not left:
                return
            if time.monotonic() > deadline:
                for pid in left:
                    os.kill(int(pid), signal.SIGKILL)
                self.fail(f"ranks still running after mpirun was killed: {left}")
            time.sleep(0.2)

    @staticmethod
    def command_line(pid: str) -> bytes:
        try:
            return Path(f"/proc/{pid}/cmdline").read_bytes()
        except OSError:
            return b""

    def test_6_a_closed_loop_starts_and_stays_on_its_constraints(self):
        # the table sets the crank's rate alone; each sample starts projected onto the loop
        result = self.gencoord("four_bar.toml", "--ranks", "1", folder="loop")
        self.assertSucceeded(result)
        self.assertIn("status      8 ok, 0 failed", result.stdout)
        final = self.results(self.home / "loop" / "four_bar.h5")["final_q"]
        a, b, c, d = 0.3, 0.8, 0.6, 0.7  # the model's lengths
        for crank, coupler, rocker in final:
            gap = math.hypot(a * math.cos(crank) + b * math.cos(coupler) - d - c * math.cos(rocker),
                             a * math.sin(crank) + b * math.sin(coupler) - c * math.sin(rocker))
            self.assertLess(gap, 1e-12)
        self.assertGreater(max(abs(q[0]) for q in final), 20)  # driven cranks turn many times

    def test_7_a_free_body_is_swept_on_its_speeds(self):
        result = self.gencoord("floating.toml", "--ranks", "1", folder="floating")
        self.assertSucceeded(result)
        self.assertIn("status      4 ok, 0 failed", result.stdout)
        report = self.results(self.home / "floating" / "floating.h5")
        self.assertEqual(report["shapes"]["final_q"], [4, 12])
        self.assertEqual(report["shapes"]["final_v"], [4, 10])
        self.assertEqual(report["shapes"]["trajectory_v"], [4, 5, 10])
        self.assertEqual(report["speeds"][3:6], ["trunk_wx", "trunk_wy", "trunk_wz"])
        # sample 2 sets the trunk's qx to 0.5 in the initial quaternion, the turn rpy = (0.1,
        # 0.2, 0) of the file's Free origin, and starts from it normalized
        w, x, y, z = (math.cos(0.1) * math.cos(0.05), 0.5, math.sin(0.1) * math.cos(0.05),
                      -math.sin(0.1) * math.sin(0.05))
        norm = math.sqrt(w * w + x * x + y * y + z * z)
        for got, expected in zip(report["trajectory_q"][2][0][3:7], (w, x, y, z)):
            self.assertAlmostEqual(got, expected / norm, places=14)
        for q in report["final_q"] + [point for sample in report["trajectory_q"]
                                      for point in sample]:
            for first in (3, 7):
                self.assertAlmostEqual(math.hypot(*q[first:first + 4]), 1.0, places=13)
        self.assertTrue(all(math.isfinite(v) for sample in report["final_v"] for v in sample))
        self.assertLess(max(report["energy_drift"]), 1e-8)  # no damping, no motor torque

    def test_3_failing_samples_are_recorded_and_the_run_goes_on(self):
        result = self.gencoord("failing.toml", "--ranks", "2", folder="failing")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"status      1 ok, 3 failed \(.*"
                                        r"mass_matrix_not_positive_definite")
        report = self.results(self.home / "failing" / "failing.h5")
        # samples: (m2, g) = (1, 9.81), (1, 1e300), (0, 9.81), (0, 1e300)
        self.assertEqual(report["status"][0], "ok")
        self.assertEqual(report["status"][2:], ["mass_matrix_not_positive_definite"] * 2)
        self.assertNotIn(report["status"][1], ("ok", "pending"))
        self.assertEqual(report["error"][0], "")
        self.assertTrue(report["error"][1])

    def test_4_a_bad_sweep_file_is_one_line(self):
        (self.home / "bad.toml").write_text(SMALL.replace("dt = 0.01", "dt = -1"))
        result = self.gencoord("bad.toml", folder="bad")
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr.strip().count("\n"), 0, result.stderr)
        self.assertRegex(result.stderr, r"bad\.toml:6: error: integration\.dt: expects a "
                                        r"positive step")

    def test_5_a_rank_that_dies_is_reported(self):
        run = subprocess.Popen([sys.executable, str(GENCOORD), "sweep", "longer.toml",
                                "--ranks", "2", "-o", "dies"], cwd=self.home,
                               env=self.environment, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, start_new_session=True)
        table = str(self.home / "dies" / "longer.table").encode()
        try:
            seen = run.stdout.readline()  # the preflight line: samples, steps, file size
            seen += run.stdout.readline()  # the first progress line: the ranks are working
            ranks = []
            deadline = time.monotonic() + 60
            while len(ranks) < 2 and time.monotonic() < deadline:
                ranks = sorted(int(pid) for pid in os.listdir("/proc") if pid.isdigit()
                               and table in self.command_line(pid)
                               and b"mpirun" not in self.command_line(pid))
                time.sleep(0.05)
            self.assertEqual(len(ranks), 2, seen)
            os.kill(ranks[-1], signal.SIGKILL)
            seen += run.stdout.read()
            status = run.wait(timeout=120)
        finally:
            if run.poll() is None:
                os.killpg(run.pid, signal.SIGKILL)
            run.stdout.close()
        self.assertEqual(status, 1, seen)
        self.assertIn("exited on signal 9", seen)
        self.assertIn("the sweep stopped", seen)
        self.assertIn("--resume runs the rest", seen)


if __name__ == "__main__":
    unittest.main()
