#!/usr/bin/env python3
"""The README's commands, run as written (issue 22): every line of its bash blocks and its Python publisher.

Run by scripts/test.sh with the built workspace sourced. A private roscore; HOME is a fresh folder (the README
writes ~/my_robot.yaml). Per line:
- the Quick start's two scripts and the clone-and-build lines of "The ordinary ROS way" are what this very run does
  (test.sh installed, built and is testing); of the apt line, the package list it extracts is checked instead;
- `roslaunch` starts in the background: a launch that ends by itself must end with status 0 (the demo), one that
  keeps running must still run after a few seconds without an error in its output, and stays up for the lines after
  it (dynparam) until the next launch;
- every other line must exit 0.
The Python publisher runs against the node the README's "Running it" block leaves up, and must get estimates
back: slips defined, rolling without slip, valid. Exit status 1 on any failure.
"""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# (a launch that ends by itself ends quietly: no required node reported dead)
ERROR_MARKERS = ("[ERROR]", "RLException", "Traceback", "ERROR:", "REQUIRED process")


def blocks(text):
    """(language, code) of every fenced block."""
    return [(m.group(1), m.group(2)) for m in re.finditer(r"^```(\w*)\n(.*?)^```", text, re.S | re.M)]


def lines(code):
    """Command lines, backslash continuations joined, comments and blanks dropped."""
    out, pending = [], ""
    for raw in code.splitlines():
        line = pending + raw
        if line.rstrip().endswith("\\"):
            pending = line.rstrip()[:-1] + " "
            continue
        pending = ""
        if line.strip() and not line.strip().startswith("#"):
            out.append(line.strip())
    return out


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


class Runner:
    def __init__(self, home):
        self.env = dict(os.environ, HOME=home, PYENV_VERSION="system")
        self.env["PATH"] = "/usr/bin:" + self.env.get("PATH", "")
        self.env["ROS_MASTER_URI"] = "http://localhost:%d" % free_port()
        self.home = home
        self.failures = []
        self.launch = None  # the launch left running, (command, process, log path)
        self.core = subprocess.Popen(["roscore", "-p", self.env["ROS_MASTER_URI"].rsplit(":", 1)[1]], env=self.env,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        for _ in range(100):
            if subprocess.run(["rostopic", "list"], env=self.env, capture_output=True).returncode == 0:
                break
            time.sleep(0.2)

    def report(self, ok, line, why=""):
        print("  %s  %s%s" % ("ok  " if ok else "FAIL", line, ("   (" + why + ")") if why else ""), flush=True)
        if not ok:
            self.failures.append("%s: %s" % (line, why))

    def stop_launch(self):
        if self.launch:
            _, process, _ = self.launch
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
            self.launch = None

    def roslaunch(self, line):
        self.stop_launch()
        log = tempfile.NamedTemporaryFile("w+", suffix=".log", delete=False, dir=self.home)
        process = subprocess.Popen(["bash", "-c", line], env=self.env, cwd=self.home, stdout=log, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        # a launch that ends by itself (the demo) has a minute or two; one that keeps a node up, a few seconds to fail
        deadline = time.time() + (180.0 if "demo.launch" in line else 8.0)
        while time.time() < deadline and process.poll() is None:
            time.sleep(0.2)
        output = open(log.name).read()
        marker = next((m for m in ERROR_MARKERS if m in output), None)
        if process.poll() is not None:
            ok = process.returncode == 0 and marker is None
            self.report(ok, line, "ended with status %d%s" % (process.returncode, ", " + marker if marker else ""))
            if not ok:
                print(output[-3000:])
        else:
            self.report(marker is None, line, "running" + (", " + marker + " in its output" if marker else ""))
            if marker:
                print(output[-3000:])
            self.launch = (line, process, log.name)

    def run(self, line):
        done = subprocess.run(["bash", "-c", line], env=self.env, cwd=self.home, capture_output=True, text=True, timeout=600)
        self.report(done.returncode == 0, line, "status %d" % done.returncode)
        if done.returncode != 0:
            print(done.stdout[-2000:], done.stderr[-2000:])

    def apt_list(self, line):
        # the list the line extracts from lib.sh must name packages, all installed by this run's install step
        extract = re.search(r"\$\((sed .*)\)", line).group(1).replace("sphere_contact_estimator/scripts/lib.sh",
                                                                    os.path.join(REPO, "scripts", "lib.sh"))
        names = subprocess.run(["bash", "-c", extract], capture_output=True, text=True).stdout.split()
        missing = [n for n in names if subprocess.run(["dpkg-query", "-W", "-f=${db:Status-Status}", n],
                                                      capture_output=True, text=True).stdout != "installed"]
        self.report(len(names) > 10 and not missing, line, "%d packages extracted, not installed: %s" %
                    (len(names), " ".join(missing) or "none"))

    def publisher(self, code):
        """The README's publisher against the node left running: estimates must come back, rolling without slip."""
        if not self.launch or "/my_robot/odometry" not in self.launch[0]:
            self.report(False, "Python publisher", "no node left running on /my_robot/odometry by the README's blocks")
            return
        path = os.path.join(self.home, "sphere_odometry.py")
        with open(path, "w") as f:
            f.write(code)
        # Ctrl-C as a terminal delivers it: a run in the background (CI) inherits SIGINT ignored, and a SIGINT that
        # reaches the publisher before rospy.init_node installs its handler would then be lost (seen: the loop ran on)
        err_path = os.path.join(self.home, "sphere_odometry.err")
        started = time.time()
        with open(err_path, "w") as err:
            publisher = subprocess.Popen(["/usr/bin/python3", path], env=dict(self.env, PYTHONFAULTHANDLER="1"),
                                         stdout=subprocess.DEVNULL, stderr=err, start_new_session=True,
                                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        echo = subprocess.run(["timeout", "20", "rostopic", "echo", "-n", "50", "-p", "/contact_estimate/slips_defined",
                               ], env=self.env, capture_output=True, text=True)
        one = subprocess.run(["timeout", "20", "rostopic", "echo", "-n", "1", "/contact_estimate"], env=self.env,
                             capture_output=True, text=True)
        fields = one.stdout
        seen = "echo status %d and %d after %.1f s" % (echo.returncode, one.returncode, time.time() - started)
        os.killpg(publisher.pid, signal.SIGINT)
        try:
            publisher.wait(10)
        except subprocess.TimeoutExpired:  # a publisher Ctrl-C cannot end is the README's fault: say so, go on
            os.killpg(publisher.pid, signal.SIGABRT)  # PYTHONFAULTHANDLER: every thread's stack to its stderr
            try:
                publisher.wait(5)
            except subprocess.TimeoutExpired:
                os.killpg(publisher.pid, signal.SIGKILL)
                publisher.wait()
            self.report(False, "Python publisher (README: Publishing it)", "still running 10 s after SIGINT (%s)" % seen)
            print(echo.stderr[-1000:], one.stderr[-1000:], open(err_path).read()[-6000:])
            return
        defined = [l.split(",")[-1] in ("1", "True") for l in echo.stdout.splitlines()[1:]]

        def value(name):
            m = re.search(r"^%s: (\S+)" % name, fields, re.M)
            return m.group(1) if m else None
        m = re.search(r"^slip:\s*\n\s*x: (\S+)\n\s*y: (\S+)", fields, re.M)
        ok = len(defined) == 50 and all(defined) and m is not None and \
            abs(float(m.group(1))) < 1e-6 and abs(float(m.group(2))) < 1e-6 and value("rolling_speed") is not None and \
            abs(float(value("rolling_speed")) - 0.5) < 1e-9
        self.report(ok, "Python publisher (README: Publishing it)",
                    "%d estimates with slips defined, slip %s, rolling_speed %s; %s" %
                    (sum(defined), m.groups() if m else None, value("rolling_speed"), seen))
        if not ok:
            print(echo.stderr[-1000:], one.stderr[-1000:], open(err_path).read()[-3000:])

    def close(self):
        self.stop_launch()
        os.killpg(self.core.pid, signal.SIGINT)
        self.core.wait(20)


def main():
    text = open(os.path.join(REPO, "README.md")).read()
    home = tempfile.mkdtemp(prefix="sce_readme_")
    runner = Runner(home)
    pending = []
    try:
        for language, code in blocks(text):
            if language == "python":
                pending.append(code)
                continue
            if language != "bash":
                continue
            for line in lines(code):
                if line.startswith("./scripts/"):
                    runner.report(True, line, "this run: scripts/test.sh installs, builds and tests")
                elif re.match(r"(mkdir -p ~/catkin_ws|git clone|cd ~/catkin_ws|source devel/setup.bash|catkin_make run_tests)", line):
                    runner.report(True, line, "the workspace this run built")
                elif line.startswith("sudo apt-get install $(sed"):
                    runner.apt_list(line)
                elif line.startswith("roslaunch "):
                    runner.roslaunch(line)
                else:
                    runner.run(line)
            # the publisher needs the node a block leaves running on its topic
            if pending and runner.launch and "/my_robot/odometry" in runner.launch[0] and "config:=" in runner.launch[0]:
                for code in pending:
                    runner.publisher(code)
                pending = []
        for code in pending:
            runner.publisher(code)
    finally:
        runner.close()
        shutil.rmtree(home, ignore_errors=True)
    if runner.failures:
        print("README commands: %d failed:\n  %s" % (len(runner.failures), "\n  ".join(runner.failures)))
        return 1
    print("README commands: all ran as written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
