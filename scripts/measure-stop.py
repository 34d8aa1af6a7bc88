#!/usr/bin/env python3
"""How quickly `gusuku-bake bake` stops on SIGTERM, at random moments, on a loaded machine (issue 39 item 5).

Usage: scripts/measure-stop.py SITE.json WORK_DIR [--signals N] [--samples S] [--load SITE.json] [--seed K]
                               [--bake PATH]

1. Bakes SITE uninterrupted into WORK_DIR/reference (kept between runs), timing it.
2. With --load, keeps a second bake of that site running beside the trials (WORK_DIR/load, --force, restarted
   whenever it ends), so the stopped bake shares the cores as it would on a busy build machine.
3. N trials into WORK_DIR/stopped, each the same command (so each resumes the last one's work): the first SIGTERM
   at a moment drawn uniformly from the start to 110 % of the time the reference took to write its set (setup
   included, and the start of the runtime pack's encoding after it); every
   fourth trial sends a second SIGTERM 0.05-0.5 s after the first. It records the time from the first signal
   (and from the second) to the process's exit, its status and which message it printed. A trial whose bake
   finished before its signal is checked against the reference and started afresh.
4. Runs the same command to the end and compares every EXR of the stopped-and-resumed set with the reference's,
   byte for byte.
Prints one line a trial and a summary; exits 1 when a stop took over 1.5 s, a status was not 130, or a file
differs. Uses the standard library only.
"""
import argparse
import filecmp
import os
import random
import shutil
import signal
import subprocess
import sys
import time

STOP_LIMIT_SECONDS = 1.5  # the promise (baker/src/bake_stop_signals.h): ended within this of the first signal


def bake_command(bake, site, out, samples):
    command = [bake, "bake", site, "-o", out, "--quiet"]
    if samples:
        command += ["--samples", str(samples)]
    return command


def exr_names(folder):
    return sorted(name for name in os.listdir(folder) if name.endswith(".exr"))


def same_exrs(reference, actual):
    """The names of the reference's EXRs that the other set lacks or holds with other bytes."""
    differing = []
    for name in exr_names(reference):
        path = os.path.join(actual, name)
        if not os.path.exists(path) or not filecmp.cmp(os.path.join(reference, name), path, shallow=False):
            differing.append(name)
    return differing


def check_and_clear(reference, stopped, label):
    """Compares a completed set with the reference, says so, and removes it; returns the failures."""
    differing = same_exrs(reference, stopped)
    print(f"{label}: {'identical to the reference' if not differing else 'DIFFERS: ' + ', '.join(differing)}")
    shutil.rmtree(stopped, ignore_errors=True)
    return [f"{label}: the set differs"] if differing else []


def message_kind(stderr_text):
    if "interrupted before tracing began" in stderr_text:
        return "setup"
    if "interrupted twice" in stderr_text:
        return "second signal"
    if "interrupted while writing the runtime pack" in stderr_text:
        return "packing"
    if "stopped without waiting" in stderr_text:
        return "deadline"
    if "the work done is saved" in stderr_text:
        return "checkpointed"
    return "none"


class Load:
    """A second bake kept running beside the trials."""

    def __init__(self, bake, site, out, samples):
        self.command = bake_command(bake, site, out, samples) + ["--force"]
        self.process = None

    def keep_running(self):
        if self.process is None or self.process.poll() is not None:
            self.process = subprocess.Popen(self.command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def stop(self):
        if self.process is not None and self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("site")
    parser.add_argument("work")
    parser.add_argument("--signals", type=int, default=40)
    parser.add_argument("--samples", type=int, default=0, help="--samples for every bake (default: the site's)")
    parser.add_argument("--load", help="a site to keep baking beside the trials")
    parser.add_argument("--seed", type=int, default=39)
    parser.add_argument("--bake", default="build/baker/gusuku-bake")
    args = parser.parse_args()
    random.seed(args.seed)
    os.makedirs(args.work, exist_ok=True)

    reference = os.path.join(args.work, "reference")
    load = Load(args.bake, args.load, os.path.join(args.work, "load"), args.samples) if args.load else None
    if load:
        load.keep_running()
    if not os.path.exists(os.path.join(reference, "manifest.json")):
        # The time to the set's manifest (the bake's last write; the runtime pack follows it).
        start = time.monotonic()
        process = subprocess.Popen(bake_command(args.bake, args.site, reference, args.samples),
                                   stdout=subprocess.DEVNULL)
        while not os.path.exists(os.path.join(reference, "manifest.json")) and process.poll() is None:
            time.sleep(0.05)
        reference_seconds = time.monotonic() - start
        if process.wait() != 0:
            sys.exit("measure-stop: the reference bake failed")
        with open(os.path.join(args.work, "reference_seconds.txt"), "w") as file:
            file.write(f"{reference_seconds}\n")
    with open(os.path.join(args.work, "reference_seconds.txt")) as file:
        reference_seconds = float(file.read())
    print(f"reference bake: its set written after {reference_seconds:.1f} s{' (beside the load)' if load else ''}")

    stopped = os.path.join(args.work, "stopped")
    shutil.rmtree(stopped, ignore_errors=True)
    command = bake_command(args.bake, args.site, stopped, args.samples)
    err_path = os.path.join(args.work, "trial.err")
    failures, first_latencies, second_latencies, kinds = [], [], [], {}
    completed_sets = 0  # sets completed by resumes and compared with the reference
    for trial in range(args.signals):
        if load:
            load.keep_running()
        if os.path.exists(os.path.join(stopped, "manifest.json")):
            # The last trial's resume completed the set (its stop came in the runtime pack's encoding): check it
            # and start afresh, so that the trials keep landing in setup and tracing.
            failures += check_and_clear(reference, stopped, f"before trial {trial + 1}: the resumed set was complete")
            completed_sets += 1
        second = trial % 4 == 3
        # From the start (setup) to a little past the set's last write (into the runtime pack's encoding).
        delay = random.uniform(0.0, 1.1 * reference_seconds)
        with open(err_path, "w") as err:
            process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=err)
            time.sleep(delay)
            if process.poll() is not None:  # finished before its signal: check it, start afresh
                failures += check_and_clear(reference, stopped, f"trial {trial + 1}: the bake finished before "
                                                                f"{delay:.2f} s")
                completed_sets += 1
                continue
            first_signal = time.monotonic()
            process.send_signal(signal.SIGTERM)
            second_signal = None
            if second:
                time.sleep(random.uniform(0.05, 0.5))
                if process.poll() is None:
                    second_signal = time.monotonic()
                    process.send_signal(signal.SIGTERM)
            status = process.wait()
            ended = time.monotonic()
        with open(err_path) as err:
            kind = message_kind(err.read())
        latency = ended - first_signal
        first_latencies.append(latency)
        kinds[kind] = kinds.get(kind, 0) + 1
        line = f"trial {trial + 1:2d}: signal at {delay:5.2f} s, ended {latency:.3f} s after it, status {status}, {kind}"
        if second_signal is not None:
            second_latencies.append(ended - second_signal)
            line += f", {ended - second_signal:.3f} s after the second signal"
        print(line, flush=True)
        if latency > STOP_LIMIT_SECONDS:
            failures.append(f"trial {trial + 1}: {latency:.2f} s")
        # 130: the bake's own stop. -SIGTERM: the signal's default action, before the bake installed its signal
        # thread (the process's first few milliseconds) or, before issue 39's fix, while the pack was written.
        if status not in (130, -signal.SIGTERM):
            failures.append(f"trial {trial + 1}: status {status}")

    if load:
        load.stop()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    differing = same_exrs(reference, stopped)
    print(f"resumed to the end: {len(exr_names(stopped))} EXRs, "
          f"{'every one byte-identical to the uninterrupted bake' if not differing else 'DIFFERING: ' + ', '.join(differing)}")
    if differing:
        failures.append("the resumed set differs")
    completed_sets += 1
    print(f"{completed_sets} sets completed by resumes after stops, each compared with the reference")
    if first_latencies:
        ordered = sorted(first_latencies)
        print(f"{len(ordered)} stops: first signal to exit median {ordered[len(ordered) // 2]:.3f} s, "
              f"max {ordered[-1]:.3f} s (limit {STOP_LIMIT_SECONDS} s); messages {kinds}")
    if second_latencies:
        print(f"{len(second_latencies)} second signals: to exit max {max(second_latencies):.3f} s")
    if failures:
        print("NOT held: " + "; ".join(failures))
        return 1
    print("held: every stop within the limit, status 130, the work resumed byte-identically")
    return 0


if __name__ == "__main__":
    sys.exit(main())
