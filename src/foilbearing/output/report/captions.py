"""Figures of the report: embedded PNGs with the paper's captions."""

from __future__ import annotations

import base64
import re
import struct
from collections.abc import Mapping, Sequence
from html import escape
from pathlib import Path
from typing import Any

from foilbearing.output.report.sections import _FIG14
from foilbearing.output.result import orbit_figure_run

__all__ = ["png_size"]


PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


_SUBSYNC = (
    "Fig. 15: filtered sub-synchronous amplitude of the vertical journal motion (the whirl "
    "and whip), 1X removed by order tracking, against speed."
)


_CAPTIONS = {
    "fig05b_stack_displacement.png": "Fig. 5(b): PZT stack displacement versus driving voltage "
    "(the synthetic measurements shipped in foilbearing/data) with the fitted curves.",
    "fig06_stack_stiffness.png": "Fig. 6(b, c): stack displacement versus static load and the "
    "identified stack stiffness of stacks #1-#3.",
    "stack_displacement.png": "PZT stack displacement versus driving voltage from the "
    "case's no-load test file, with the fitted curves (as the paper's Fig. 5b).",
    "stack_stiffness.png": "PZT stack displacement versus static load from the case's "
    "stiffness test file, and the identified stack stiffness (as the paper's Fig. 6b-c).",
    "static_vs_voltage.png": "Eccentricity, attitude angle, minimum film and power loss "
    "against the actuators' voltage (all the same) at the case speed and load.",
    "preloads_vs_voltage.png": "Piezoelectric preload and actuator pressure of each "
    "actuator against the voltage at the case speed and load.",
    "fig07_stiffness_function.png": "Fig. 7: structural stiffness function k(θ) for several "
    "smoothness constants α.",
    "fig08_preloads.png": "Fig. 8: base preloads r_p(θ) of the C-GFB at 0/50/100/150 V and the "
    "shims of the shimmed GFB.",
    "fig09_midplane.png": "Fig. 9: mid-plane gas-film pressure and film thickness at 50 krpm, "
    "(a) C-GFB and (b) shimmed GFB.",
    "fig10_actuator_pressure.png": "Fig. 10: local gas-film pressure at θ = 60°, 180° and 300° "
    "versus speed, C-GFB and shimmed GFB.",
    "fig11_preload.png": "Fig. 11: piezoelectric preloads at 60°, 180° and 300° versus speed "
    "(C-GFB).",
    "fig12_eccentricity.png": "Fig. 12: journal eccentricity and attitude angle versus speed, "
    "C-GFB and shimmed GFB.",
    "coefficients_50krpm_150V.png": "Not in the paper: stiffness and damping coefficients versus "
    "excitation frequency at 50 krpm and 150 V.",
    "stability_map.png": "Not in the paper: linear stability over speed and voltage with the "
    "onset speeds; compare with the nonlinear orbits of Figs. 13-15.",
    "uncertainty_bands.png": "Beyond the paper: median and 5-95 % band of each output over "
    "the inputs the paper leaves open; triangles are the paper's points, drawn on the bands, "
    "never fitted to them (its whip frequencies come from nonlinear speed-ups).",
    "uncertainty_indices.png": "Beyond the paper: first-order (filled) and total (outline) "
    "sensitivity indices of each uncertain input, with 95 % bootstrap half-widths.",
    "schedule.png": "Beyond the paper: the voltage schedule, least-drag actuator voltages "
    "with a log decrement of at least the margin at each speed; its log decrement and its "
    "power loss beside a constant 150 V.",
    "schedule_subsync.png": "Beyond the paper: sub-synchronous amplitude of the paper's "
    "speed-up (1 g·mm) on the schedule, beside 0 V, 150 V from the start and the paper's "
    "ramp at 6.0-6.5 s.",
    "schedule_power.png": "Beyond the paper: film power loss during the same four speed-ups.",
    "fig15_subsync.png": _SUBSYNC,
    "fig15_subsync_control.png": _SUBSYNC + " Variant: control before our 0 V run's divergence.",
    "fig15_subsync_1gmm.png": _SUBSYNC + " Variant: the protocol as published, 1 g·mm imbalance.",
    "orbit_subsync.png": _SUBSYNC,
    "stability_map_shimmed.png": "Linear stability of the shimmed GFB over speed and shim "
    "voltage, with the onset speeds.",
    "stack_design.png": "The linear onset at the design voltage against the stack's stiffness "
    "K_p under each reading of the actuator, beside the shimmed GFB.",
    "whirl_branches.png": "Limit-cycle branches from each linear onset: whirl amplitude "
    "against speed, stable and unstable cycles, per reading and voltage.",
    "whirl_branch.png": "The limit-cycle branch from the linear onset: whirl amplitude and "
    "frequency against speed, stable and unstable cycles (the Hopf bifurcation's type).",
    "static_vs_speed.png": "Eccentricity, attitude angle, minimum film and power loss against "
    "speed at the case load.",
    "load_capacity.png": "Eccentricity, attitude angle, minimum film and power loss against "
    "the load at the case speed, up to the largest load the film carries.",
    "coefficients_vs_speed.png": "Synchronous stiffness and damping coefficients (excitation "
    "at the running speed) against speed.",
    "log_decrement.png": "Log decrement of the least stable whirl mode against speed; the "
    "linear onset is where it crosses zero.",
    "onset_vs_shims.png": "Linear onset speed and whirl frequency against the shims' thickness.",
    "onset_vs_voltage.png": "Linear onset speed and whirl frequency against the actuators' "
    "voltage.",
    "campbell.png": "Campbell diagram of the rotor on its foil bearings: whirl frequencies "
    "and log decrements of the modes against speed, with the onset.",
    "mode_shapes.png": "Mode shapes of the rotor on its bearings at the onset speed (or the "
    "top speed where it is stable).",
    "unbalance_response.png": "Synchronous response of the rotor to its unbalance against "
    "speed, at the bearings and the disks.",
    "rotor_orbit.png": "Nonlinear speed-up of the rotor on its foil bearings: the journals' "
    "motion against speed.",
}

#: Figures whose names carry a speed (rpm): what each shows at that speed.
_AT_SPEED = {
    "film_map_": "Film pressure (next to the mid-plane and its axial mean) and film "
    "thickness around the bearing at {speed}, case load.",
    "coefficients_": "Stiffness and damping coefficients against excitation frequency at {speed}.",
}

#: The speed-up of the study of any bearing (files ``speedup_<kind>.png``).
_SPEEDUP = {
    "transient": "Speed-up of the case's imbalance: journal motion e_X, e_Y and speed.",
    "waterfall": "Speed-up: waterfall of e_X, the whirl's frequency against speed.",
    "waterfall3d": "Speed-up: waterfall of e_X in 3-D.",
    "orbits": "Speed-up: journal orbits at selected speeds.",
}


def png_size(data: bytes) -> tuple[int, int] | None:
    """Width and height from a PNG's IHDR chunk, or None if ``data`` is not a PNG."""
    if len(data) < 24 or data[:8] != PNG_SIGNATURE or data[12:16] != b"IHDR":
        return None
    width, height = struct.unpack(">II", data[16:24])
    return (width, height) if width > 0 and height > 0 else None


#: File prefix of the study's runs under the paper's reading of the actuator, and its words.
READING_TAG = "lobe-held_"
READING_TEXT = "Under the paper's reading of the actuator in the film (lobe + held)."


def _figure(out_dir: Path, name: str, runs: Sequence[Mapping[str, Any]] = ()) -> str:
    """A <figure> with the PNG embedded, or a note where the file is missing or not a PNG.

    ``runs``: the orbit stage's runs, which caption the speed-ups' figures.
    """
    caption = _caption(name, runs)
    path = out_dir / name
    data = path.read_bytes() if path.is_file() else b""
    size = png_size(data)
    if size is None:
        why = "is missing" if not data else "is not a PNG"
        return f'<p class="note">Figure <code>{escape(name)}</code> {why}: {escape(caption)}</p>'
    uri = "data:image/png;base64," + base64.b64encode(data).decode("ascii")
    return (
        f'<figure><img src="{uri}" alt="{escape(caption)}" width="{size[0]}" '
        f'height="{size[1]}"><figcaption>{escape(caption)} '
        f"<code>{escape(name)}</code></figcaption></figure>"
    )


def _caption(name: str, runs: Sequence[Mapping[str, Any]] = ()) -> str:
    """The paper's caption of a figure, or for a speed-up's figure its run's; else the name.

    A run of the paper's protocol (series "paper protocol": the case's imbalance,
    0 V or the ramps at 6.0-6.5 s) shows Fig. 13 or 14 itself; the study's other
    runs are "like" them, with the run said in full.
    """
    if name in _CAPTIONS:
        return _CAPTIONS[name]
    for head, text in _AT_SPEED.items():
        m = re.fullmatch(re.escape(head) + r"(\d+)rpm\.png", name)
        if m:
            return text.format(speed=f"{int(m.group(1)):,} rpm")
    kind = name.removeprefix("speedup_").removesuffix(".png")
    if name.startswith("speedup_") and kind in _SPEEDUP:
        return _SPEEDUP[kind]
    if name.startswith(READING_TAG):  # a run of the study's paper-reading stage
        return _caption(name.removeprefix(READING_TAG), runs).rstrip(".") + f". {READING_TEXT}"
    found = orbit_figure_run(name, runs)
    if found is None:
        return name
    _, run, kind = found
    v = float(run.get("voltage_V") or 0.0)
    like = "" if run.get("series") == "paper protocol" else "Like "
    fig13 = "Fig. 13" if not like and v == 0 else "Like Fig. 13"
    fig14 = f"{like}Fig. 14({_FIG14[v]})" if v in _FIG14 else "Like Fig. 14"
    what = {
        "transient": (f"{fig13}(a)" if v == 0 else fig14) + ": journal motion e_X, e_Y and speed",
        "waterfall": f"{fig13}(b): waterfall of e_X",
        "waterfall3d": f"{fig13}(b): waterfall of e_X in 3-D",
        "orbits": "Not in the paper: journal orbits at selected speeds",
    }[kind]
    run_text = run.get("description") or run.get("label")
    reading = f" {READING_TEXT}" if str(run.get("label", "")).startswith(READING_TAG) else ""
    return f"{what}; speed-up 3-90 krpm, {run_text}.{reading}"
