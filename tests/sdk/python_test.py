"""The Python module `foveal` from the build tree, on the system python3 with NumPy:
the live fovea and settings from a real foveald, and gaze logs and traces as arrays.
Usage: python_test.py BUILD_DIR SOURCE_DIR  (ctest: FovealPython)."""
import dataclasses
import math
import os
import signal
import struct
import subprocess
import sys
import tempfile
import time
import unittest
import warnings

BUILD, SOURCE = sys.argv.pop(1), sys.argv.pop(1)
sys.path.insert(0, os.path.join(SOURCE, "sdk", "python"))
import numpy as np  # noqa: E402

import foveal  # noqa: E402

LOG = os.path.join(SOURCE, "data", "gaze", "vive_pro_eye_TESTNA01.csv")


class Live(unittest.TestCase):
    """One foveald (replay of the bundled log, gaze only) for the live tests."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory(prefix="foveal-python-")
        d = cls.dir.name
        cls.env = dict(os.environ, FOVEAL_SHM_NAME=f"/foveal-python-test-{os.getpid()}",
                       XDG_RUNTIME_DIR=os.path.join(d, "run"), XDG_CONFIG_HOME=os.path.join(d, "config"))
        os.makedirs(cls.env["XDG_RUNTIME_DIR"])
        profiles = os.path.join(cls.env["XDG_CONFIG_HOME"], "foveal", "profiles")
        os.makedirs(profiles)
        with open(os.path.join(profiles, "bob.json"), "w") as f:
            f.write('{"format":"foveal-profile v1","dominant_eye":"left","sigma_d":2.4,"sigma_nd":3.2}')
        os.environ["FOVEAL_SHM_NAME"] = cls.env["FOVEAL_SHM_NAME"]
        cls.out = os.path.join(d, "out")
        cls.foveald = subprocess.Popen(
            [os.path.join(BUILD, "bin", "foveald"), "--replay", LOG, "--no-render", "--loop", "--end", "12",
             "--duration", "600", "-q", "--out", cls.out], env=cls.env)

    @classmethod
    def tearDownClass(cls):
        if cls.foveald.poll() is None:
            cls.foveald.kill()
            cls.foveald.wait()
        cls.dir.cleanup()

    def client(self):
        deadline = time.monotonic() + 60
        while True:
            try:
                return foveal.Client()
            except foveal.ClientError as e:
                if e.code != foveal.NO_WRITER or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)

    def first_fovea(self, c):
        deadline = time.monotonic() + 60
        while True:
            try:
                return c.read()
            except foveal.ClientError as e:
                if e.code != foveal.NO_DATA or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)

    def test_1_reads_the_live_fovea_inside_the_viewport(self):
        with self.client() as c:
            f = self.first_fovea(c)
            self.assertGreater(f.frame, 0)
            self.assertEqual((f.eye_width, f.eye_height), (1440, 1600))  # the Vive Pro Eye's eye viewport
            for e in (0, 1):
                self.assertTrue(math.isfinite(f.x[e]) and 0 <= f.x[e] <= f.eye_width, f)
                self.assertTrue(math.isfinite(f.y[e]) and 0 <= f.y[e] <= f.eye_height, f)
                self.assertIn(f.state[e], range(5))
            # The next frame is waited for (60 s hang guard), not expected within a time.
            deadline = time.monotonic() + 60
            while c.read().frame <= f.frame and time.monotonic() < deadline:
                time.sleep(0.01)
            self.assertGreater(c.read().frame, f.frame, "the fovea moves on at the replay's rate")

    def test_2_sees_a_settings_change_and_a_profile_switch(self):
        with self.client() as c:
            before = c.settings()
            self.assertEqual((before.sigma_d, before.sigma_nd, before.dominant_eye), (2.0, 3.0, "right"))  # the defaults
            self.assertIsInstance(before.dominant_eye, str)
            self.assertEqual((before.dominant_eye.index, int(before.dominant_eye)), (1, 1))
            with warnings.catch_warnings(record=True) as caught:  # code of the int days still works, and is told
                warnings.simplefilter("always")
                self.assertTrue(before.dominant_eye == 1 and before.dominant_eye != 0)
            self.assertTrue(caught and all(issubclass(w.category, DeprecationWarning) for w in caught), caught)
            subprocess.run([os.path.join(BUILD, "bin", "foveal"), "ctl", "set", "sigma_d=2.75", "sigma_nd=3.25"],
                           env=self.env, check=True, stdout=subprocess.DEVNULL)
            after = c.settings()  # the reply comes after the change is in the block
            self.assertEqual((after.sigma_d, after.sigma_nd), (2.75, 3.25))
            self.assertGreater(after.generation, before.generation)
            # A profile switch, too.
            subprocess.run([os.path.join(BUILD, "bin", "foveal"), "ctl", "use", "bob"], env=self.env, check=True,
                           stdout=subprocess.DEVNULL)
            bob = c.settings()
            self.assertEqual((bob.sigma_d, bob.sigma_nd, bob.dominant_eye), (2.4, 3.2, "left"))
            self.assertGreater(bob.generation, after.generation)

    def test_2b_motion_and_prediction_as_foveald_predicts(self):
        # (runs before test_3, which stops foveald) A fovea and its motion from the live
        # block, and predict() moving each predictable eye by foveald's rule.
        f32 = lambda v: struct.unpack("f", struct.pack("f", v))[0]  # noqa: E731 (the C side's float)
        with self.client() as c:
            self.first_fovea(c)
            deadline, pair, moving = time.monotonic() + 60, None, None
            while time.monotonic() < deadline and moving is None:
                f = c.read()
                m = c.motion()
                self.assertGreaterEqual(m.frame, f.frame, "the motion is written before its fovea")
                if m.frame == f.frame:  # else foveald published in between: read both again
                    pair = (f, m)
                    if any(m.predictable[e] and (m.velocity_x[e] or m.velocity_y[e]) for e in (0, 1)):
                        moving = pair
                time.sleep(0.005)
            self.assertIsNotNone(moving, "no predictable, moving eye in 60 s of the replay")
        f, m = moving
        self.assertIsInstance(m, foveal.Motion)
        self.assertTrue(all(isinstance(p, bool) for p in m.predictable), m)
        self.assertTrue(all(math.isfinite(v) for v in m.velocity_x + m.velocity_y + m.lag_x + m.lag_y), m)
        # At the sample's time (or before it) nothing moves.
        self.assertEqual(foveal.predict(f, m, f.t_ns), f)
        self.assertEqual(foveal.predict(f, m, f.t_ns - 5_000_000), f)
        # 21 ms on (a display's wait): x + lag + velocity * h, clamped inside the viewport.
        h_ns = 21_000_000
        p = foveal.predict(f, m, f.t_ns + h_ns)
        self.assertEqual((p.t_ns, p.frame, p.state), (f.t_ns, f.frame, f.state), "the sample's time and frame stay")
        for e in (0, 1):
            if not m.predictable[e]:
                self.assertEqual((p.x[e], p.y[e]), (f.x[e], f.y[e]), f"eye {e} is held")
                continue
            want_x = min(max(f.x[e] + m.lag_x[e] + m.velocity_x[e] * h_ns * 1e-9, 0.0), f.eye_width)
            want_y = min(max(f.y[e] + m.lag_y[e] + m.velocity_y[e] * h_ns * 1e-9, 0.0), f.eye_height)
            self.assertAlmostEqual(p.x[e], f32(want_x), delta=1e-3, msg=f"eye {e}: {f} {m}")
            self.assertAlmostEqual(p.y[e], f32(want_y), delta=1e-3, msg=f"eye {e}: {f} {m}")
        # Past the 50 ms horizon: as far as the horizon, no further.
        self.assertEqual(foveal.predict(f, m, f.t_ns + 80_000_000),
                         foveal.predict(f, m, f.t_ns + foveal.PREDICT_MAX_HORIZON_NS))
        # Another fovea's motion, a zero viewport and wrong types are errors that say so.
        other = dataclasses.replace(m, frame=m.frame + 1)
        with self.assertRaises(foveal.ClientError) as caught:
            foveal.predict(f, other, f.t_ns + h_ns)
        self.assertEqual(caught.exception.code, foveal.NO_DATA)
        self.assertIn(f"frame {f.frame}", str(caught.exception))
        with self.assertRaises(foveal.ClientError) as caught:
            foveal.predict(dataclasses.replace(f, eye_width=0), m, f.t_ns + h_ns)
        self.assertEqual(caught.exception.code, foveal.INVALID_ARGUMENT)
        for bad in ((f, m, 1.5), (f, m, 2**63), (m, f, 0), (f, None, 0)):
            with self.assertRaises(foveal.ClientError) as caught:
                foveal.predict(*bad)
            self.assertEqual(caught.exception.code, foveal.INVALID_ARGUMENT, bad)
        closed = self.client()
        closed.close()
        with self.assertRaises(foveal.ClientError) as caught:
            closed.motion()
        self.assertEqual(caught.exception.code, foveal.INVALID_ARGUMENT)

    def test_3_a_stopped_foveald_is_no_writer(self):
        c = self.client()
        self.first_fovea(c)
        self.foveald.send_signal(signal.SIGTERM)
        self.assertEqual(self.foveald.wait(10), 0)
        with self.assertRaises(foveal.ClientError) as caught:
            c.read()
        self.assertEqual(caught.exception.code, foveal.NO_WRITER)
        c.close()
        with self.assertRaises(foveal.ClientError) as caught:
            foveal.Client()
        self.assertEqual(caught.exception.code, foveal.NO_WRITER)
        self.assertIn("is foveald running?", str(caught.exception))
        # Its trace, as arrays.
        t = foveal.read_trace(os.path.join(self.out, "trace.csv"))
        self.assertGreater(len(t), 10)
        self.assertEqual(t["t_ns"][0], 0)
        self.assertTrue(np.all((t["left_state"] <= foveal.LOST)))
        self.assertTrue(np.all((t["left_x_px"] >= 0) & (t["left_x_px"] <= 1440)))


class Files(unittest.TestCase):
    def test_the_bundled_log_as_arrays(self):
        log = foveal.read_gaze_log(LOG)
        self.assertEqual((log.version, log.rate_hz, len(log)), (2, 120.0, 1518))  # as `foveal log validate` says
        self.assertEqual(log.meta["source"], "sranipal:TESTNA01_2D_Fist3.csv")
        self.assertEqual(log["t_ns"].dtype, np.int64)
        self.assertEqual(log["t_ns"][0], 0)
        self.assertTrue(np.all(np.diff(log["t_ns"]) > 0))
        self.assertAlmostEqual(float(log["left_dir_x"][0]), -0.1235046, places=7)
        self.assertAlmostEqual(float(log["head_qz"][0]), 0.032027364, places=9)
        # combined_valid 0: its fields are empty, NaN here.
        self.assertEqual(int(log["combined_valid"][0]), 0)
        self.assertTrue(np.isnan(log["combined_dir_x"][0]))
        # Invalid left eye (bit 0 clear) in about 14% of the samples, as `log validate` reports.
        invalid = np.mean((log["left_valid"] & 1) == 0)
        self.assertAlmostEqual(float(invalid), 0.1403, places=3)

    def write(self, text):
        f = tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False)
        f.write(text)
        f.close()
        self.addCleanup(os.unlink, f.name)
        return f.name

    def v1(self, rows):
        cols = ",".join(foveal.files.gaze_log_columns(1))
        return "# foveal-gaze-log v1\n# rate_hz=120\n" + cols + "\n" + "".join(r + "\n" for r in rows)

    def row(self, t, x="0.1"):
        eye = f"15,{x},0.2,-0.97,1,2,3,3.5,0.9"
        return f"{t},{eye},{eye},0,,,,,,"

    def test_a_v1_log_with_markers(self):
        path = self.write(self.v1([self.row(0), "#mark,5,trial 1, start", self.row(10), self.row(20)]))
        log = foveal.read_gaze_log(path)
        self.assertEqual((log.version, len(log)), (1, 3))
        self.assertEqual(log.markers, [(5, "trial 1, start")])
        self.assertNotIn("head_valid", log.samples.dtype.names)

    def test_bad_logs_name_the_line_and_the_column(self):
        cases = [
            (self.v1([self.row(0), self.row(10, x="abc")]), 5, "left_dir_x: 'abc' is not a number"),
            (self.v1([self.row(0), self.row(10, x="nan")]), 5, "left_dir_x: 'nan' is not finite"),
            (self.v1([self.row(10), self.row(10)]), 5, "t_ns: 10 repeats the previous timestamp"),
            (self.v1([self.row(0), self.row(10)[:-3]]), 5, "missing"),
            (self.v1([]), 3, "no samples"),
            ("# foveal-gaze-log v3\n", 1, "v3 is not supported"),
            (self.v1([self.row(0)]).replace("right_openness", "right_open"), 3, "column 19 is 'right_open'"),
            (self.v1([self.row(0)]).replace("\n", "\r\n"), 1, "CRLF"),
            (self.v1([self.row(0)])[:-1], 4, "truncated last row"),
            (self.v1([self.row(0), "#note"]), 5, "marker row"),
        ]
        for text, line, what in cases:
            with self.subTest(what=what):
                with self.assertRaises(foveal.FormatError) as caught:
                    foveal.read_gaze_log(self.write(text))
                self.assertEqual(caught.exception.line, line, str(caught.exception))
                self.assertIn(what, str(caught.exception))

    def test_a_trace_with_a_bad_state_names_it(self):
        header = "t_ns,left_state,left_x_px,left_y_px,left_confidence,right_state,right_x_px,right_y_px,right_confidence\n"
        path = self.write(header + "0,fixation,1.5,2.5,0.90,blink,3,4,0.00\n7,dozing,1,2,0.5,lost,720,800,0\n")
        with self.assertRaises(foveal.FormatError) as caught:
            foveal.read_trace(path)
        self.assertIn(":3: left_state: 'dozing' is not a state", str(caught.exception))


CASES = os.path.join(SOURCE, "tests", "sdk", "gaze_log_cases")


class BothReaders(unittest.TestCase):
    """read_gaze_log and foveal's own reader (`foveal log validate`) take and refuse the
    same logs: every file of tests/sdk/gaze_log_cases through both, good_* accepted and
    bad_* refused by each."""

    def test_accept_and_refuse_the_same_files(self):
        names = sorted(n for n in os.listdir(CASES) if n.endswith(".csv"))
        self.assertGreater(len(names), 40)
        for name in names:
            with self.subTest(file=name):
                path = os.path.join(CASES, name)
                cli = subprocess.run([os.path.join(BUILD, "bin", "foveal"), "log", "validate", path],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, errors="replace")
                self.assertIn(cli.returncode, (0, 2), cli.stderr)
                try:
                    foveal.read_gaze_log(path)
                    python_error = None
                except foveal.FormatError as e:
                    python_error = str(e)
                want_ok = name.startswith("good_")
                self.assertEqual(cli.returncode == 0, want_ok, f"foveal log validate: {cli.stderr.strip()}")
                self.assertEqual(python_error is None, want_ok, f"read_gaze_log: {python_error}")

    def test_a_fifo_is_refused_without_blocking(self):
        d = tempfile.mkdtemp(prefix="foveal-python-fifo-")
        self.addCleanup(os.rmdir, d)
        fifo = os.path.join(d, "log.csv")
        os.mkfifo(fifo)
        self.addCleanup(os.unlink, fifo)
        with self.assertRaises(foveal.FormatError) as caught:
            foveal.read_gaze_log(fifo)
        self.assertIn("not a regular file", str(caught.exception))


# Run as the second user: plants KIND at PATH, as `mkfifo -m 666 /dev/shm/foveal-fovea-<uid>`
# did in issue 38. A block gets a live writer's header, so only owner and mode tell it apart.
PLANT = r"""
import os, struct, sys, time
kind, path = sys.argv[1], sys.argv[2]
if kind == "fifo":
    os.mkfifo(path, 0o666); os.chmod(path, 0o666)
elif kind == "symlink":
    target = path + "-target"
    os.mkfifo(target, 0o666); os.chmod(target, 0o666); os.symlink(target, path)
else:
    mode = int(kind[len("block"):], 8)
    block = bytearray(200)
    struct.pack_into("<III", block, 0, 0x41564F46, 3, 200)                  # magic "FOVA", version 3, size
    struct.pack_into("<qII", block, 136, time.monotonic_ns() + 10**9, os.getpid(), 1)  # heartbeat, pid, live
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, mode)
    os.fchmod(fd, mode); os.write(fd, bytes(block)); os.close(fd)
"""

# Run as the victim: opens the block, prints the error code and message.
OPEN = r"""
import sys, foveal
try:
    foveal.Client(sys.argv[1]).close()
    print("0 opened")
except foveal.ClientError as e:
    print(e.code, e)
"""


class PlantedBlocks(unittest.TestCase):
    """Issue 38 item 1: what another user plants at a block name never hangs or fools
    foveal.Client(): a FIFO (open used to wait for a writer, for ever), a symbolic link,
    their own block open to all, and for root their private one. The planting runs as a
    user this test creates; root opens, in a child with a generous time limit, so a hang
    fails the test instead of stalling it."""

    GUARD_S = 30

    @classmethod
    def setUpClass(cls):
        if os.geteuid() != 0:
            raise unittest.SkipTest("needs root to create a second user (useradd); CI runs the tests as root")
        cls.user = f"fovpy{os.getpid()}"
        deadline = time.monotonic() + 60  # parallel tests contend for /etc/passwd's lock (a hang guard)
        while True:
            if subprocess.run(["useradd", "--system", "--no-create-home", "--user-group", "--shell", "/usr/sbin/nologin",
                               cls.user], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0:
                break
            if time.monotonic() > deadline:
                raise AssertionError(f"useradd {cls.user} failed")
            time.sleep(0.1)

    @classmethod
    def tearDownClass(cls):
        deadline = time.monotonic() + 60
        while subprocess.run(["userdel", cls.user], stderr=subprocess.DEVNULL).returncode != 0 and time.monotonic() < deadline:
            time.sleep(0.1)
        subprocess.run(["groupdel", cls.user], stderr=subprocess.DEVNULL)  # where userdel left the group

    def remove_later(self, path):
        def remove():
            if os.path.lexists(path):
                os.unlink(path)
        self.addCleanup(remove)

    def planted_open(self, kind):
        name = f"/foveal-python-planted-{os.getpid()}-{kind}"
        path = "/dev/shm" + name
        self.remove_later(path)
        self.remove_later(path + "-target")
        subprocess.run([sys.executable, "-c", PLANT, kind, path], user=self.user, group=self.user, extra_groups=[],
                       check=True)
        env = dict(os.environ, PYTHONPATH=os.path.join(SOURCE, "sdk", "python"))
        try:
            done = subprocess.run([sys.executable, "-c", OPEN, name], env=env, capture_output=True, text=True,
                                  timeout=self.GUARD_S)
        except subprocess.TimeoutExpired:
            self.fail(f"foveal.Client({name!r}) did not return within {self.GUARD_S} s: it waits on a planted {kind}")
        self.assertEqual(done.returncode, 0, done.stderr)
        code, message = done.stdout.strip().split(" ", 1)
        return int(code), message

    def test_what_another_user_plants_is_refused_at_once(self):
        uid = subprocess.run(["id", "-u", self.user], capture_output=True, text=True, check=True).stdout.strip()
        cases = [("fifo", "is a FIFO"), ("symlink", "symbolic link"), ("block0666", f"belongs to uid {uid}"),
                 ("block0600", f"belongs to uid {uid}")]
        for kind, naming in cases:
            with self.subTest(kind=kind):
                code, message = self.planted_open(kind)
                self.assertEqual(code, foveal.NOT_FOVEALDS, message)
                self.assertIn(naming, message)


class MarkArguments(unittest.TestCase):
    """foveal.mark refuses, before anything is sent, what the C library cannot be handed:
    ctypes would cut the text at a NUL, and a lone surrogate has no UTF-8 form."""

    def refused(self, *args, **kwargs):
        with self.assertRaises(foveal.ClientError) as caught:
            foveal.mark(*args, **kwargs)
        self.assertEqual(caught.exception.code, foveal.INVALID_ARGUMENT, str(caught.exception))
        return str(caught.exception)

    def test_nul_surrogates_and_wrong_types_are_invalid_arguments(self):
        nowhere = os.path.join(tempfile.gettempdir(), f"foveal-python-no-socket-{os.getpid()}")
        self.assertIn("NUL", self.refused("a\x00b", socket=nowhere))
        self.assertIn("character 2", self.refused("a\x00b", socket=nowhere))
        self.assertIn("surrogate", self.refused("trial \udc80", socket=nowhere))
        self.assertIn("str", self.refused(b"trial", socket=nowhere))
        self.assertIn("NUL", self.refused("trial", socket=nowhere + "\x00x"))
        self.assertIn("socket", self.refused("trial", socket=5))
        with self.assertRaises(foveal.ClientError) as caught:  # a good text is sent: nobody listens there
            foveal.mark("trial 1", socket=nowhere)
        self.assertEqual(caught.exception.code, foveal.NO_WRITER)


if __name__ == "__main__":
    unittest.main(verbosity=2)
