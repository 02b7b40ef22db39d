"""Progress display of a run: one bar for the whole run, one for the operating point in work.

Built on :mod:`rich`.  The run bar shows points done / total and the estimated time left (from
the mean duration of the points finished in this session); the point bar shows the fraction the
analyser reports (rotor speeds swept, root-finding steps) and the time spent on it.  ``quiet``
gives a do-nothing display with the same interface, so the workflow never tests for it.
"""

from __future__ import annotations

import sys
import time
from typing import IO

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TaskProgressColumn,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)


class RunProgress:
    """Context manager driving the progress bars.

    Parameters
    ----------
    total : number of operating points of the run.
    done : points already finished (resumed runs).
    quiet : show nothing.
    stream : where to draw (stderr by default, so stdout stays clean for messages).
    """

    def __init__(self, total: int, done: int = 0, quiet: bool = False, stream: IO | None = None):
        self.total = total
        self.done = done
        self.quiet = quiet
        self._durations: list[float] = []
        self._t0 = 0.0
        self._progress: Progress | None = None
        self._run_task = None
        self._point_task = None
        if not quiet:
            console = Console(file=stream or sys.stderr)
            self._progress = Progress(
                TextColumn("{task.description}", justify="left"),
                BarColumn(bar_width=30),
                MofNCompleteColumn(),
                TaskProgressColumn(),
                TextColumn("elapsed"),
                TimeElapsedColumn(),
                TextColumn("left"),
                TimeRemainingColumn(),
                console=console,
                transient=False,
            )

    # -- context -----------------------------------------------------------------------------
    def __enter__(self) -> RunProgress:
        if self._progress is not None:
            self._progress.start()
            self._run_task = self._progress.add_task("run", total=self.total, completed=self.done)
        return self

    def __exit__(self, *exc) -> None:
        if self._progress is not None:
            self._progress.stop()

    # -- points --------------------------------------------------------------------------------
    def start_point(self, label: str) -> None:
        self._t0 = time.perf_counter()
        if self._progress is None:
            return
        if self._point_task is not None:
            self._progress.remove_task(self._point_task)
        self._point_task = self._progress.add_task(f"  {label}", total=100)

    def update_point(self, fraction: float, text: str | None = None) -> None:
        """Report progress within the current point (``fraction`` in [0, 1])."""
        if self._progress is None or self._point_task is None:
            return
        kw = {"completed": 100.0 * min(max(float(fraction), 0.0), 1.0)}
        if text:
            kw["description"] = f"  {text}"
        self._progress.update(self._point_task, **kw)

    def finish_point(self, status: str = "ok", message: str | None = None) -> float:
        """Close the current point; return its duration (s)."""
        dt = time.perf_counter() - self._t0
        self._durations.append(dt)
        self.done += 1
        if self._progress is not None:
            if self._point_task is not None:
                self._progress.remove_task(self._point_task)
                self._point_task = None
            self._progress.update(self._run_task, completed=self.done)
            if message:
                self._progress.console.print(message)
        return dt

    def log(self, message: str) -> None:
        if self._progress is not None:
            self._progress.console.print(message)

    @property
    def mean_duration(self) -> float:
        return sum(self._durations) / len(self._durations) if self._durations else float("nan")
