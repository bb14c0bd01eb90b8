"""Finding and running contact_eval, shared by the plot scripts."""
import json
import shutil
import subprocess
import sys


def contact_eval_command(path=None):
    """The command that runs contact_eval: PATH if given, else through rosrun."""
    if path:
        return [path]
    if shutil.which("rosrun"):
        return ["rosrun", "sphere_contact_estimator", "contact_eval"]
    sys.exit("contact_eval not found: source the workspace's devel/setup.bash or pass --contact-eval")


def run_json(cmd, args):
    """Runs contact_eval with args and returns its JSON; RuntimeError with its stderr if it fails (safe to
    call from worker threads: the caller decides how to stop)."""
    args = list(args)
    try:
        out = subprocess.run(cmd + args, capture_output=True, text=True)
    except OSError as err:
        raise RuntimeError("cannot run %s: %s" % (cmd[0], err))
    if out.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s" % (" ".join(cmd + args), out.returncode, out.stderr.strip()))
    return json.loads(out.stdout)
