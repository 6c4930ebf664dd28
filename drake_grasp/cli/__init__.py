"""The `drake-grasp` command.

Every subcommand prints a one-line summary (or one JSON object with --json) and takes --out (and
--seed where a run has randomness). Exit codes are a contract: 2 for bad input (an unknown object, a
broken mesh, a malformed scenario, a number out of range, an output path that cannot be written, a
results folder another run holds), reported as one line on stderr before any work starts, never a
traceback; 1 for a run that could not be carried out; 130 for Ctrl-C and 143 for SIGTERM (both stop
the run's workers).

The commands, one module per kind (each adds its parsers and runs them):

* `single`: demo, trial, plan-eigengrasp, resemble (one run in this process);
* `sweeps`: fig4, fig6, fig7, novel, reproduce (many trials on an executor, resumable);
* `studies`: capture, sensitivity, near-primitives (beyond the paper, the same way);
* `object_tools`: objects generate, objects check;
* `models`: the robot's SDF files from its facts;
* `common`: the options and input checks they share, and how a single run's result is printed.
"""

import argparse
import signal
import sys
import threading

from drake_grasp.cli import models, object_tools, single, studies, sweeps
from drake_grasp.cli.common import UsageError

__all__ = ["Terminated", "UsageError", "main"]


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it unwinds like Ctrl-C (workers stopped, locks
    released); exit code 143."""


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="drake-grasp",
        description="Compliance-centric grasping (BarrettHand on a Barrett WAM) in Drake.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    single.add_demo(sub)
    sweeps.add_fig4(sub)
    single.add_trial(sub)
    sweeps.add_fig6(sub)
    sweeps.add_fig7(sub)
    sweeps.add_novel(sub)
    studies.add_capture(sub)
    studies.add_sensitivity(sub)
    studies.add_near_primitives(sub)
    studies.add_exploration(sub)
    sweeps.add_reproduce(sub)
    single.add_plan_eigengrasp(sub)
    single.add_resemble(sub)
    object_tools.add_objects(sub)
    models.add_models(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `drake-grasp` console script; returns the exit code."""
    import warnings

    from drake_grasp.objects import MeshNote, UnstablePoseWarning

    args = _parser().parse_args(argv)
    if argv is None and hasattr(signal, "SIGPIPE") and threading.current_thread() is threading.main_thread():
        # As a console command (not called from Python): output piped into a reader that stops early
        # (`| head`) ends the command quietly, as other command-line tools do, not with a traceback.
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)

    def one_line(message, category, *rest, **kwargs):
        kind = "note" if issubclass(category, MeshNote) else "warning"
        print(f"drake-grasp {args.command}: {kind}: {message}", file=sys.stderr, flush=True)

    try:
        with warnings.catch_warnings(), _sigterm_as_interrupt():
            warnings.simplefilter("once", UnstablePoseWarning)
            warnings.showwarning = one_line
            return args.run(args)
    except (UsageError, ValueError, FileNotFoundError) as e:
        # ObjectError and scenario errors are ValueErrors with one-line messages.
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"drake-grasp {args.command}: error: {message}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        # A run that could not be carried out (e.g. the arm cannot reach the object): one line, exit 1.
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"drake-grasp {args.command}: failed: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as e:
        terminated = isinstance(e, Terminated)
        print(f"drake-grasp {args.command}: {'terminated' if terminated else 'interrupted'}", file=sys.stderr)
        return 143 if terminated else 130


class _sigterm_as_interrupt:
    """While active (in the main thread), SIGTERM raises `Terminated`, which unwinds like Ctrl-C."""

    def __enter__(self):
        self.previous = None
        if threading.current_thread() is threading.main_thread():
            self.previous = signal.signal(signal.SIGTERM, self._raise)
        return self

    @staticmethod
    def _raise(signum, frame):
        raise Terminated()

    def __exit__(self, *exc):
        if self.previous is not None:
            signal.signal(signal.SIGTERM, self.previous)

