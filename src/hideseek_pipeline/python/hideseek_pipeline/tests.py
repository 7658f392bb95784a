"""make test: every test (core gtests, rostests, the Python tests) through catkin_make run_tests,
then the verdict from the results: catkin_make run_tests exits 0 even when tests fail, so the
count comes from build/test_results, and the last line is `N passed, M failed`."""
import glob
import os
import re
import subprocess
import xml.etree.ElementTree as ET

# The lines of catkin_make's output worth seeing while the tests run.
SHOWN = re.compile(r"^\[ *(RUN|OK|FAILED|PASSED) *\]|^\[ROSTEST\]|^SUMMARY|^ \* RESULT|^  \* |Error|error:|Failure|FAIL")
PORT = 11411  # tests that start roscore need a free port of their own


def tally(results):
    """(passed, failed, skipped) over every JUnit file under `results`, each parsed once: a file that
    cannot be parsed counts as one failure; a skipped case counts as neither and is named, as 'name
    (why)', so that make test shows a case that did not run, not one taken for passed."""
    passed = failed = 0
    skipped = []
    for path in sorted(glob.glob(os.path.join(results, "**", "*.xml"), recursive=True)):
        try:
            cases = list(ET.parse(path).getroot().iter("testcase"))
        except ET.ParseError:
            failed += 1
            continue
        for case in cases:
            skip = case.find("skipped")
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
            elif skip is None:
                passed += 1
            else:
                why = (skip.get("message") or skip.text or "").strip().splitlines()
                skipped.append("%s%s" % (case.get("name", "?"), " (%s)" % why[0] if why else ""))
    return passed, failed, skipped


def run_tests(root, say=print):
    """Runs every test of the workspace at `root`; returns 0 when every test passed."""
    results = os.path.join(root, "build", "test_results")
    subprocess.run(["rm", "-rf", results])
    cmd = ("source scripts/env.sh && catkin_make run_tests -j1 -DPYTHON_EXECUTABLE=/usr/bin/python3 "
           "-DPython3_EXECUTABLE=/usr/bin/python3")
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % PORT)
    with subprocess.Popen(["bash", "-c", cmd], cwd=root, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, errors="replace") as p:
        for line in p.stdout:
            if SHOWN.search(line):
                say(line.rstrip())
    say("")
    # A target that fails to build stops run_tests part way: the results then hold only what ran
    # before it, and every test after it is missing, not passed.
    stopped = p.returncode != 0
    summary = subprocess.run(["bash", "-c", "source scripts/env.sh && catkin_test_results build/test_results --all"],
                             cwd=root, capture_output=True, text=True)
    with open(os.path.join(root, "build", "test_summary.txt"), "w") as f:
        f.write(summary.stdout + summary.stderr)
    lines = [x for x in (summary.stdout + summary.stderr).splitlines() if not x.startswith("Skipping")]
    for line in lines[-40:]:
        say(line)
    passed, failed, not_run = tally(results) if os.path.isdir(results) else (0, 0, [])
    if passed + failed == 0:
        failed = 1  # no result at all: the tests did not run
    elif summary.returncode != 0 and failed == 0:
        failed = 1
    if stopped:
        failed += 1  # the run itself, which stopped before every test ran
        say("catkin_make run_tests stopped with exit status %d before every test ran (a target failed to build: "
            "its error is above); the counts cover only the tests that ran" % p.returncode)
    if not_run:
        say("%d skipped, counted neither passed nor failed: %s" % (len(not_run), "; ".join(not_run)))
    say("%d passed, %d failed" % (passed, failed))
    return 0 if summary.returncode == 0 and failed == 0 else 1
