"""Fault injection: sweeps killed at random moments, damaged results files and a second writer, then
a plain rerun whose records must equal a clean run's.

For each sweep (Fig. 4 --quick; a small Fig. 6 of oracle trials: two primitives, one trial, a 0.5 s
hold) this script:

1. runs it cleanly into a fresh folder: the reference records;
2. repeatedly starts it into a second folder and, at a random moment (seeded), sends the main process
   SIGKILL or SIGTERM; 5 s later it checks that none of the processes the run had started is alive;
3. between runs, damages random lines of the results file (a line cut halfway, cut after its key
   fields, a field made non-numeric, two lines joined, the last line torn), starts a second writer
   while a run holds the folder (it must be refused at once, exit 2), and once reruns the Fig. 6
   sweep with another scenario into the same folder (records of other inputs, never to be used);
4. reruns the sweep plainly to completion and compares its records with the reference: every field
   but the wall time.

It prints, and writes as Markdown (--report), the counts: runs killed, lines damaged, second writers
refused, workers left alive, and records lost, doubled or stale (which must all be 0). Exit code 0
when every must-be-zero count is 0, else 1.

    .venv/bin/python scripts/fault_injection.py                 # about 10 minutes on 2 cores
    .venv/bin/python scripts/fault_injection.py --rounds 2 --report ''
"""

import argparse
import csv
import dataclasses
import os
import pathlib
import random
import signal
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
IGNORED = {"wall_time", "check"}  # fields that may differ between runs (the checksum covers the wall time)
STARTUP = 5.0  # s before a sweep starts its first task (imports, workers), about
SHORT_SCENARIO = "default:\n  protocol:\n    execution:\n      hold_time: 0.5\n"
OTHER_SCENARIO = "default:\n  contact:\n    friction: 0.0\n  protocol:\n    execution:\n      hold_time: 0.5\n"


@dataclasses.dataclass
class Sweep:
    """A sweep as a command line (without --out) and the results file it writes."""

    name: str
    argv: list[str]
    csv_name: str
    key: list[str]


@dataclasses.dataclass
class Counts:
    runs_killed: int = 0
    runs_finished_before_the_kill: int = 0
    sigkill: int = 0
    sigterm: int = 0
    lines_damaged: int = 0
    damaged_reported: int = 0
    second_writers_refused: int = 0
    second_writers_after_the_first: int = 0  # the first run ended meanwhile: the second may run
    second_writers_admitted: int = 0
    other_input_runs: int = 0
    workers_alive_after_kill: int = 0
    records_lost: int = 0
    records_doubled: int = 0
    records_stale: int = 0
    tracebacks: int = 0

    MUST_BE_ZERO = ("second_writers_admitted", "workers_alive_after_kill", "records_lost", "records_doubled",
                    "records_stale", "tracebacks")


def command(sweep: Sweep, out: pathlib.Path, extra: list[str] = ()) -> list[str]:
    return [sys.executable, "-m", "drake_grasp.cli", *sweep.argv, *extra, "--out", str(out)]


def environment() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return env


def run_to_end(sweep: Sweep, out: pathlib.Path, counts: Counts, extra: list[str] = ()) -> subprocess.CompletedProcess:
    done = subprocess.run(command(sweep, out, extra), env=environment(), capture_output=True, text=True,
                          cwd=ROOT)
    counts.tracebacks += "Traceback" in done.stderr
    counts.damaged_reported += done.stderr.count("damaged record, recomputing")
    if done.returncode != 0:
        raise SystemExit(f"{sweep.name}: a plain run failed ({done.returncode}): {done.stderr.strip()[-500:]}")
    return done


def descendants(pid: int) -> set[int]:
    """The processes under pid (children, grandchildren, ...), from /proc."""
    parents = {}
    for entry in pathlib.Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
                parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
    found, frontier = set(), {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def alive(pid: int) -> bool:
    try:
        stat = pathlib.Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


def killed_run(sweep: Sweep, out: pathlib.Path, delay: float, sig: int, counts: Counts,
               second_writer: bool) -> None:
    """Starts the sweep, optionally tries a second writer meanwhile, and sends `sig` after `delay` s."""
    process = subprocess.Popen(command(sweep, out), env=environment(), stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True, cwd=ROOT)
    start = time.monotonic()
    if second_writer:  # once the run holds the folder, a second run into it must be refused at once
        while not (out / ".drake-grasp.lock").exists() and process.poll() is None and time.monotonic() - start < delay:
            time.sleep(0.05)
        if (out / ".drake-grasp.lock").exists() and process.poll() is None:
            second = subprocess.run(command(sweep, out), env=environment(), capture_output=True, text=True,
                                    cwd=ROOT)
            refused = second.returncode == 2 and "another drake-grasp run" in second.stderr
            counts.second_writers_refused += refused
            if not refused and process.poll() is not None and second.returncode == 0:
                counts.second_writers_after_the_first += 1
            elif not refused:
                counts.second_writers_admitted += 1
                print(f"second writer admitted: {second.returncode} {second.stderr.strip()[-300:]}", flush=True)
            counts.tracebacks += "Traceback" in second.stderr
            counts.damaged_reported += second.stderr.count("damaged record, recomputing")
    seen: set[int] = set()
    while time.monotonic() - start < delay and process.poll() is None:
        seen |= descendants(process.pid)
        time.sleep(0.1)
    if process.poll() is not None:  # finished before the kill
        stderr = process.stderr.read()
        counts.tracebacks += "Traceback" in stderr
        counts.damaged_reported += stderr.count("damaged record, recomputing")
        counts.runs_finished_before_the_kill += 1
        return
    seen |= descendants(process.pid)
    process.send_signal(sig)
    counts.runs_killed += 1
    counts.sigkill += sig == signal.SIGKILL
    counts.sigterm += sig == signal.SIGTERM
    process.wait()
    stderr = process.stderr.read()
    counts.tracebacks += "Traceback" in stderr
    counts.damaged_reported += stderr.count("damaged record, recomputing")
    time.sleep(5.0)
    counts.workers_alive_after_kill += sum(alive(pid) for pid in seen)


def damage(path: pathlib.Path, rng: random.Random, count: int) -> int:
    """Damages `count` random data lines of a results file, each in one of five ways (cut halfway,
    cut after its key fields, a numeric field made "banana", joined with the next line, or the last
    line torn without its newline); returns how many lines it damaged."""
    if not path.exists():
        return 0
    lines = [l for l in path.read_text().split("\n") if l]  # header first
    tear = False
    done = 0
    for _ in range(count):
        if len(lines) < 3:
            break
        i = rng.randrange(1, len(lines) - 1)
        line = lines[i]
        kind = rng.choice(["cut", "cut_after_key", "non_numeric", "join", "tear_last"])
        if kind == "cut":
            lines[i] = line[: rng.randrange(1, len(line))]
        elif kind == "cut_after_key":
            lines[i] = ",".join(line.split(",")[:5]) + ","
        elif kind == "non_numeric":
            fields = line.split(",")
            numeric = [j for j, f in enumerate(fields) if _is_number(f)] or [0]
            fields[rng.choice(numeric)] = "banana"
            lines[i] = ",".join(fields)
        elif kind == "join":
            lines[i: i + 2] = [line + lines[i + 1]]
        else:
            tear = True
        done += 1
    text = "\n".join(lines) + "\n"
    if tear:
        text = text[: len(text) - 1 - len(lines[-1]) // 2]
    path.write_text(text)
    return done


def _valid_lines(path: pathlib.Path) -> int:
    """How many records a results file holds (lines after the header; damaged ones are few)."""
    if not path.exists():
        return 0
    return max(0, path.read_text().count("\n") - 1)


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def records(path: pathlib.Path, key: list[str], fingerprints: set[str] | None = None) -> tuple[dict, int]:
    """The file's records by key (of the given fingerprints, or all), without the ignored fields, and
    how many keys appear more than once."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if fingerprints is not None:
        rows = [r for r in rows if r.get("fingerprint") in fingerprints]
    out, doubled = {}, 0
    for r in rows:
        k = tuple(r[f] for f in key)
        doubled += k in out
        out[k] = {f: v for f, v in r.items() if f not in IGNORED}
    return out, doubled


def exercise(sweep: Sweep, work: pathlib.Path, rounds: int, rng: random.Random, counts: Counts,
             other_inputs: list[str] | None = None) -> None:
    clean_dir, dir_ = work / f"{sweep.name}-clean", work / f"{sweep.name}-faults"
    start = time.monotonic()
    run_to_end(sweep, clean_dir, counts)
    duration = time.monotonic() - start
    reference, doubled = records(clean_dir / sweep.csv_name, sweep.key)
    fingerprints = {k[0] for k in reference}
    print(f"{sweep.name}: clean run {duration:.0f} s, {len(reference)} records", flush=True)
    for r in range(rounds):
        sig = rng.choice([signal.SIGKILL, signal.SIGTERM])
        # a moment in the run: its start-up (a few seconds), then the time its missing records take
        missing = 1.0 - _valid_lines(dir_ / sweep.csv_name) / len(reference)
        delay = rng.uniform(1.0, STARTUP + max(0.0, missing) * (duration - STARTUP))
        killed_run(sweep, dir_, delay, sig, counts, second_writer=(r % 2 == 0))
        counts.lines_damaged += damage(dir_ / sweep.csv_name, rng, rng.randint(1, 3))
        if other_inputs is not None and r == 0:
            run_to_end(sweep, dir_, counts, other_inputs)  # other inputs, same folder: their own records
            counts.other_input_runs += 1
        print(f"{sweep.name}: round {r + 1}/{rounds}: {signal.Signals(sig).name} after {delay:.1f} s", flush=True)
    run_to_end(sweep, dir_, counts)
    final, doubled = records(dir_ / sweep.csv_name, sweep.key, fingerprints)
    _, doubled_any = records(dir_ / sweep.csv_name, sweep.key)
    counts.records_doubled += doubled + doubled_any
    counts.records_lost += sum(k not in final for k in reference)
    counts.records_stale += sum(k in final and final[k] != v for k, v in reference.items())
    counts.records_stale += sum(k not in reference for k in final)


def report_markdown(counts: Counts, args, seconds: float) -> str:
    rows = "\n".join(f"| {f.name.replace('_', ' ')} | {getattr(counts, f.name)} |"
                     + (" must be 0 |" if f.name in Counts.MUST_BE_ZERO else " |")
                     for f in dataclasses.fields(counts))
    ok = all(getattr(counts, name) == 0 for name in Counts.MUST_BE_ZERO)
    return (f"# Fault injection: measured\n\n"
            f"`.venv/bin/python scripts/fault_injection.py --rounds {args.rounds} --seed {args.seed}` "
            f"({seconds:.0f} s on this machine, {os.cpu_count()} cores). Fig. 4 --quick and a small Fig. 6 "
            "(sphere:0.08 and cube:0.06, oracle, 1 trial, 0.5 s hold) were each killed at random moments "
            "(SIGKILL or SIGTERM to the main process), their results files damaged at random lines, a second "
            "writer started beside a running sweep, and (Fig. 6) the sweep run once with another scenario into "
            "the same folder; then a plain rerun's records were compared with a clean run's (every field but "
            f"the wall time).\n\n| count | value | |\n|---|---|---|\n{rows}\n\n"
            f"Result: {'every must-be-zero count is 0' if ok else 'FAILED: a must-be-zero count is not 0'}.\n")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=4, help="killed runs per sweep (default 4)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the kill times, signals and damage")
    parser.add_argument("--report", default=str(ROOT / "docs/results/fault_injection.md"),
                        help="Markdown report to write ('' for none)")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    counts = Counts()
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="fault-injection-") as tmp:
        work = pathlib.Path(tmp)
        short, other = work / "short.yaml", work / "other.yaml"
        short.write_text(SHORT_SCENARIO)
        other.write_text(OTHER_SCENARIO)
        fig4 = Sweep("fig4", ["fig4", "--quick", "--workers", "2"], "fig4.csv",
                     ["fingerprint", "shape", "size", "axis", "error"])
        fig6 = Sweep("fig6", ["fig6", "--objects", "sphere:0.08,cube:0.06", "--trials", "1", "--method", "oracle",
                              "--workers", "2", "--scenario", str(short)], "fig6.csv",
                     ["fingerprint", "object", "method", "grasp", "seed"])
        exercise(fig4, work, args.rounds, rng, counts)
        # the same sweep with another scenario: the last --scenario given wins
        exercise(fig6, work, args.rounds, rng, counts, other_inputs=["--scenario", str(other)])
    seconds = time.monotonic() - start
    for f in dataclasses.fields(counts):
        print(f"{f.name}: {getattr(counts, f.name)}")
    if args.report:
        pathlib.Path(args.report).write_text(report_markdown(counts, args, seconds))
    return 0 if all(getattr(counts, name) == 0 for name in Counts.MUST_BE_ZERO) else 1


if __name__ == "__main__":
    sys.exit(main())
