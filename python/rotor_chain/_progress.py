"""Progress of the long calls that Python drives in chunks (the phase-diagram sweeps): a
``tqdm.auto`` bar, which renders as a widget in Jupyter and as a text bar in a terminal.

``progress`` is what the user passed:

- ``None`` (the default): a bar where someone watches, that is when stderr is a terminal or the
  stream of a Jupyter kernel, and nothing in a log file, a pipe or a test run;
- ``True``: a bar on stderr wherever it goes; ``False``: nothing;
- a callable: called as ``progress(done, total)`` after each chunk, and nothing else.

Without tqdm installed there is no bar and no error: where a bar would be, one line
``NAME: done/total points`` is rewritten on stderr instead.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Optional, Union

Progress = Union[None, bool, Callable[[int, int], None]]


def _watched() -> bool:
    """Whether someone watches stderr: a terminal, or a Jupyter kernel's stream (ipykernel's
    ``OutStream``, which says it is no terminal)."""
    stream = sys.stderr
    if stream is None:
        return False
    if type(stream).__module__.startswith("ipykernel"):
        return True
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


def _tqdm() -> Optional[Any]:
    """``tqdm.auto.tqdm``, or ``None`` where tqdm is not installed."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm


@contextmanager
def progress_bar(progress: Progress, total: int, name: str, unit: str = "point") -> Iterator[Callable[[int], None]]:
    """A function of the number of items done so far, for the duration of the ``with`` block;
    the bar is closed when the block ends, also by an exception (Ctrl-C included), so a notebook
    shows where it stopped."""
    if callable(progress):
        yield lambda done: progress(done, total)  # type: ignore[misc,operator]
        return
    show = _watched() if progress is None else bool(progress)
    if not show or total == 0:
        yield lambda done: None
        return
    tqdm = _tqdm()
    if tqdm is None:
        yield _plain(total, name, unit)
        return
    bar = tqdm(total=total, desc=name, unit=unit, file=sys.stderr, dynamic_ncols=True)
    try:
        yield lambda done: bar.update(done - bar.n)
    finally:
        bar.close()


def _plain(total: int, name: str, unit: str) -> Callable[[int], None]:
    """One line on stderr, rewritten: the progress without tqdm."""

    def report(done: int) -> None:
        end = "\n" if done >= total else ""
        sys.stderr.write(f"\r{name}: {done}/{total} {unit}s{end}")
        sys.stderr.flush()

    return report
