"""``foilbearing rotor``: a rotor on foil bearings, its modes (matched whirl on ROSS) and onset."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import emit

__all__ = ["cmd_rotor", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``rotor`` subcommand to the main parser's subparsers ``sub``."""
    rot = sub.add_parser(
        "rotor",
        help="a rotor on foil bearings: modes, log decrements and onset (ROSS, matched whirl)",
    )
    rot.add_argument("rotor", type=Path, help="rotor file (TOML; docs/rotor-format.md)")
    rot.add_argument(
        "--speed-range",
        default="30000rpm:60000rpm:2500rpm",
        help="speeds START:STOP:STEP of the bearings' tables and the modes (default "
        "30000rpm:60000rpm:2500rpm; about 500rpm apart near the onset reads it to 0.1 %%)",
    )
    rot.add_argument("--modes", type=int, default=4, help="modes kept at each speed (default 4)")
    rot.add_argument("--plot", metavar="DIR", type=Path, help="write campbell.png to DIR")
    rot.add_argument("--json", action="store_true", help="print one JSON object")
    rot.set_defaults(func=cmd_rotor)
    return rot


def cmd_rotor(args: argparse.Namespace) -> int:
    """Run ``rotor``; returns the exit code (0)."""
    from foilbearing.constants import RPM
    from foilbearing.errors import InputError
    from foilbearing.io import save_figure
    from foilbearing.rotor import load_rotor, rotor_onset
    from foilbearing.units import parse_speed_range

    rotor = load_rotor(args.rotor)
    speeds = parse_speed_range(args.speed_range, field="--speed-range")
    if len(speeds) < 2:
        raise InputError(f"--speed-range {args.speed_range!r}: need at least two speeds")
    if not 1 <= args.modes <= 20:
        raise InputError(f"--modes {args.modes}: allowed 1 to 20")
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    onset, whirl, modes = rotor_onset(rotor, speeds, num_modes=args.modes, progress=progress)
    out: dict[str, Any] = {
        "title": rotor.title,
        "mass_kg": rotor.mass,
        "bearings": [
            {"label": b.label, "node": b.node, "load_N": load}
            for b, load in zip(rotor.bearings, rotor.bearing_loads(), strict=True)
        ],
        "onset_speed_rpm": None if onset is None else onset / RPM,
        "whirl_frequency_Hz": whirl,
        "modes": modes.headline(),
    }
    if args.plot is not None:
        from foilbearing.output.plots.rotor import plot_campbell

        fig = plot_campbell(modes, onset, rotor.title)
        out["figures"] = [str(save_figure(fig, args.plot / "campbell.png"))]
    if args.json:
        emit(out)
        return 0
    for b in out["bearings"]:
        print(f"  {b['label']} (node {b['node']}): carries {b['load_N']:.2f} N")
    if onset is None:
        print(f"  stable up to {speeds[-1] / RPM:.0f} rpm")
    else:
        print(f"  onset {onset / RPM:.0f} rpm, whirl {whirl:.1f} Hz")
    return 0
