"""The Dask client of a sweep or sample: an existing scheduler's, or a new local cluster's.

:func:`client` connects to ``--scheduler`` (TLS from Dask's configuration) or starts a
local cluster of single-thread worker processes on 127.0.0.1. A Ctrl-C reaches the
whole process group at a terminal; the local cluster's workers leave it to this
process, which closes the cluster without distributed's logging of every connection
it loses.
"""

from __future__ import annotations

import logging
import os
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any

from foilbearing.errors import InputError

__all__ = ["DASHBOARD_ADDRESS", "TLS_KEYS", "client", "quiet_distributed"]


#: Where the local cluster's HTTP server (and dashboard, when asked for) listens: this
#: machine only, a free port.
DASHBOARD_ADDRESS = "127.0.0.1:0"


#: Dask's configuration keys of a TLS client's files (a config file or DASK_* variables).
TLS_KEYS = (
    "distributed.comm.tls.ca-file",
    "distributed.comm.tls.client.cert",
    "distributed.comm.tls.client.key",
)


def _security(scheduler: str) -> Any:
    """The client's ``distributed.Security`` for ``scheduler``: for a ``tls://`` address, the
    certificate files from Dask's configuration (docs/sweep-format.md), checked to exist;
    None (Dask's default) for any other address."""
    if not scheduler.startswith("tls://"):
        return None
    import dask
    from distributed import Security

    missing = [key for key in TLS_KEYS if not dask.config.get(key, None)]
    if missing:
        env = ", ".join("DASK_" + k.upper().replace(".", "__").replace("-", "_") for k in missing)
        raise InputError(
            f"--scheduler {scheduler!r}: a TLS scheduler needs the client's certificate files: "
            f"set {', '.join(missing)} in a Dask config file, or {env}"
        )
    for key in TLS_KEYS:
        path = Path(str(dask.config.get(key)))
        if not path.is_file():
            raise InputError(f"--scheduler {scheduler!r}: {key} = {str(path)!r}: no such file")
    return Security(require_encryption=True)


@contextmanager
def client(
    scheduler: str | None, n_workers: int | None, *, dashboard: bool = False
) -> Iterator[Any]:
    """A client on ``scheduler``, else on a new local cluster of ``n_workers`` processes.

    The local cluster listens on 127.0.0.1 only, its scheduler's HTTP server on
    :data:`DASHBOARD_ADDRESS`. Without ``dashboard`` that server has no
    dashboard, only its health and metrics routes; with it, the dashboard's
    address is printed on stderr.

    Its worker processes ignore SIGINT: a Ctrl-C at the terminal reaches the whole
    process group, and is this process's to handle (it closes the cluster, quietly),
    not each worker's to print a traceback of.
    """
    from distributed import Client, LocalCluster

    if scheduler is not None:
        security = _security(scheduler)
        try:
            client = Client(scheduler, timeout="20s", security=security)
        except OSError as exc:
            raise InputError(f"--scheduler {scheduler!r}: cannot connect ({exc})") from None
        with client:
            yield client
        return
    with _sigint_held():  # threads and worker processes started here inherit the mask
        cluster = LocalCluster(
            n_workers=n_workers or os.cpu_count() or 1,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            # Not dashboard_address=None: the scheduler's HTTP server (always started) would
            # then take port 8787, and a second cluster warn that it is in use.
            dashboard_address=DASHBOARD_ADDRESS,
            scheduler_kwargs={"dashboard": dashboard},
            silence_logs=logging.ERROR,
        )
    with cluster:
        # Stopped (Ctrl-C, an error): the workers are killed mid-task as the cluster
        # closes, and distributed would log each lost connection, here and on them.
        try:
            _release_sigint()  # a Ctrl-C held back while the cluster started is raised here
            with Client(cluster) as client:
                if dashboard:
                    import importlib.util

                    missing = importlib.util.find_spec("bokeh") is None
                    note = " (a stub: the dashboard needs bokeh, pip install bokeh)" * missing
                    print(f"dashboard: {cluster.dashboard_link}{note}", file=sys.stderr, flush=True)
                try:
                    yield client
                except BaseException:
                    with suppress(Exception):
                        client.run(quiet_distributed, callback_timeout=2)
                    raise
        except BaseException:
            quiet_distributed()
            raise


def quiet_distributed() -> None:
    """Silence distributed's logging in this process (a cluster closing on a stop)."""
    names = [n for n in logging.root.manager.loggerDict if n.startswith("distributed.")]
    for name in ("distributed", *names):
        logging.getLogger(name).setLevel(logging.CRITICAL)


def _holds_sigint() -> bool:
    import signal

    main = threading.current_thread() is threading.main_thread()
    return main and hasattr(signal, "pthread_sigmask")


@contextmanager
def _sigint_held() -> Iterator[None]:
    """SIGINT blocked in this thread while the local cluster starts (until
    :func:`_release_sigint`, or an error).

    The cluster's threads, and the worker processes they start (restarted ones too),
    inherit the blocked signal, so a Ctrl-C at the terminal, which reaches the whole
    process group, is this process's alone to handle: it closes the cluster quietly,
    where each worker would print a traceback. One pressed while the cluster starts is
    held, not lost.

    The resource tracker of ``multiprocessing`` is started first: starting it unblocks
    SIGINT in the thread that does (``multiprocessing/resource_tracker.py``), which
    would be the cluster's.
    """
    import signal
    from multiprocessing import resource_tracker

    if not _holds_sigint():
        yield
        return
    resource_tracker.ensure_running()
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    except BaseException:
        _release_sigint()
        raise


def _release_sigint() -> None:
    import signal

    if _holds_sigint():
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
