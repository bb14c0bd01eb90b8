#!/usr/bin/env python3
"""Sort ThreadSanitizer reports (scripts/test_tsan.sh) into the package's and the rest.

roscpp, boost and dynamic_reconfigure come uninstrumented from Debian: TSan does not see their atomics, so it
reports races and lock-order inversions inside them that it cannot judge (a message buffer freed on roscpp's
poll thread and read by a deserializer, shared_ptr counts). A race in this package's code has every
conflicting access in the package's sources (its src/, include/ or test/): the estimator's state is touched
only by them. So is every edge of a lock-order cycle through one of its mutexes: it is locked only there.
Such reports fail the run and are printed in full; the others are counted by kind and left in the log
directory.

Frames in libraries that the process dlopen'ed (the nodelet in Debian's manager, where the runtime is
preloaded) come unsymbolized; they are symbolized here from the build's LIB_DIR with llvm-symbolizer.

usage: tsan_reports.py REPORT_DIR REPO LIB_DIR
"""
import collections
import glob
import os
import re
import subprocess
import sys

SEPARATOR = "=================="
# the sections of a report whose stacks conflict: the two accesses of a race, the edges of a lock cycle
CONFLICT = re.compile(r"^  (Read|Write|Atomic|Previous|Mutex \S+ acquired here while holding)")


def stacks(report):
    """The conflicting sections of a report, each as its list of frames."""
    result, current = [], None
    for line in report.splitlines():
        if CONFLICT.match(line):
            current = []
            result.append(current)
        elif current is not None and re.match(r"^\s+#\d+ ", line):
            current.append(line.strip())
        elif not line.strip():
            current = None
    return result


UNSYMBOLIZED = re.compile(r"<null> <null> \((lib[^+()]+)\+(0x[0-9a-f]+)\)")


def symbolize(text, lib_dir):
    """Text with the unsymbolized frames of LIB_DIR's libraries replaced by 'function file:line (module+offset)'."""
    wanted = collections.defaultdict(set)
    for module, offset in UNSYMBOLIZED.findall(text):
        if os.path.exists(os.path.join(lib_dir, module)):
            wanted[module].add(offset)
    names = {}
    for module, offsets in wanted.items():
        offsets = sorted(offsets)
        # return addresses: the call is the instruction before
        query = "".join("0x%x\n" % (int(o, 16) - 1) for o in offsets)
        out = subprocess.run(["llvm-symbolizer-14", "--obj=" + os.path.join(lib_dir, module)], input=query,
                             capture_output=True, text=True).stdout
        for offset, block in zip(offsets, out.strip().split("\n\n")):
            lines = block.splitlines()
            names[(module, offset)] = " / ".join("%s %s" % (lines[i], lines[i + 1]) for i in range(0, len(lines) - 1, 2))
    return UNSYMBOLIZED.sub(lambda m: "%s (%s+%s)" % (names.get((m.group(1), m.group(2)), "<null> <null>"),
                                                      m.group(1), m.group(2)), text)


def main():
    report_dir, repo, lib_dir = sys.argv[1], os.path.realpath(sys.argv[2]), sys.argv[3]
    ours_pattern = re.compile(re.escape(repo) + r"/(src|include|test)/")
    ours, others = [], collections.Counter()
    for path in sorted(glob.glob(os.path.join(report_dir, "tsan*"))):
        text = symbolize(open(path, errors="replace").read(), lib_dir)
        for report in text.split(SEPARATOR):
            if "WARNING: ThreadSanitizer" not in report:
                continue
            kind = re.search(r"WARNING: ThreadSanitizer: ([^(\n]+)", report).group(1).strip()
            sections = stacks(report) or [re.findall(r"#\d+ .*", report)]
            if all(any(ours_pattern.search(frame) for frame in s) for s in sections):
                ours.append((path, report.strip()))
            else:
                summary = re.search(r"SUMMARY: ThreadSanitizer: (.*)", report)
                where = re.sub(r"\(.*?\+0x[0-9a-f]+\)|\s+", " ", summary.group(1)) if summary else kind
                others[where.strip()[:150]] += 1
    for path, report in ours:
        print("%s\n%s\n%s" % (SEPARATOR, report, SEPARATOR))
    print("ThreadSanitizer: %d reports in this package's code" % len(ours))
    print("ThreadSanitizer: %d reports inside uninstrumented libraries (roscpp, boost, dynamic_reconfigure), "
          "not judged; in %s:" % (sum(others.values()), report_dir))
    for where, count in others.most_common(8):
        print("  %4d  %s" % (count, where))
    return 1 if ours else 0


if __name__ == "__main__":
    sys.exit(main())
