"""A limit cycle's amplitude read off a branch, and its grid error (issue 49, item 1).

The readers are checked on the Hopf normal form, whose cycles grow as A² = c (ω − ω_H)
(supercritical: above the onset; subcritical: below it), so that every value they return
is known exactly.
"""

from __future__ import annotations

import math

import pytest

from foilbearing.study.bifurcation import EXTEND_LAST, amplitude_at, cycle_errors


def _branch(hopf: float, c: float, speeds: list[float], kind: str) -> dict[str, object]:
    """A normal-form branch's headline: cycles of A² = c |ω − ω_H| µm² at ``speeds`` (rpm),
    stable on a supercritical branch, unstable on a subcritical one."""
    return {
        "bifurcation_type": kind,
        "hopf_speed_rpm": hopf,
        "linear_whirl_frequency_Hz": 100.0,
        "speed_limit_rpm": None,
        "speeds_rpm": speeds,
        "amplitude_um": [math.sqrt(c * abs(w - hopf)) for w in speeds],
        "stable": [kind == "supercritical"] * len(speeds),
        "grid": [96, 4],
    }


def test_the_amplitude_between_cycles_is_the_normal_form_s() -> None:
    """Interpolated in A², a normal-form branch gives its amplitude exactly at any speed
    within it, past its last cycle by up to EXTEND_LAST of the last segment, and none
    below a supercritical onset; beyond its reach it gives nothing."""
    speeds = [79_120.0, 79_200.0, 79_400.0, 79_750.0]
    head = _branch(79_115.0, 0.04, speeds, "supercritical")
    for w in (79_117.0, 79_300.0, 79_600.0, 79_750.0 + EXTEND_LAST * 350.0):
        assert amplitude_at(head, w) == pytest.approx(math.sqrt(0.04 * (w - 79_115.0)), rel=1e-12)
    assert amplitude_at(head, 79_000.0) == 0.0
    assert amplitude_at(head, 79_750.0 + (EXTEND_LAST + 0.1) * 350.0) is None
    # a subcritical branch leaves its onset downwards: nothing above it
    down = _branch(56_943.0, 0.3, [56_940.0, 56_930.0, 56_900.0], "subcritical")
    assert amplitude_at(down, 56_920.0) == pytest.approx(math.sqrt(0.3 * 23.0), rel=1e-12)
    assert amplitude_at(down, 57_000.0) == 0.0
    assert amplitude_at({"hopf_speed_rpm": None}, 1.0) is None


def test_a_cycle_s_error_is_read_at_the_same_distance_past_each_onset() -> None:
    """Two grids whose onsets differ by 1 % and whose cycles differ by 5 % in c: the
    onset carries the onsets' difference; the largest stable cycle carries the amplitude
    difference at the same relative distance past each onset, √c₁ − √c₂ times its root,
    not the far larger difference at the same speed; a branch of another type is said."""
    coarse = _branch(79_115.0, 0.040, [79_120.0, 79_300.0, 79_745.0], "supercritical")
    fine = _branch(79_910.0, 0.038, [79_915.0, 80_100.0, 80_550.0], "supercritical")
    out = cycle_errors(coarse, fine)
    assert out["errors"]["hopf_speed_rpm"] == pytest.approx(795.0, rel=1e-12)
    past = 79_745.0 / 79_115.0 - 1.0
    a1, a2 = math.sqrt(0.040 * 630.0), math.sqrt(0.038 * 79_910.0 * past)
    assert out["errors"]["largest_stable_cycle_um"] == pytest.approx(a1 - a2, rel=1e-9)
    # at the same speed the finer grid has no cycle yet: the error would be the cycle
    assert amplitude_at(fine, 79_745.0) == 0.0
    assert out["errors"]["largest_stable_cycle_um"] < 0.1 * a1
    assert out["texts"]["largest_stable_cycle_um"] == "5.02 ± 0.11"
    # the whirl agrees to the bit: the onsets' least relative error stands
    assert out["errors"]["linear_whirl_frequency_Hz"] == pytest.approx(0.7, rel=1e-12)
    assert "largest stable cycle 5.0" in out["text"] and "Hopf 79.1 ± 0.8 krpm" in out["text"]
    # type flipped: the coarse stable cycle below its onset has no partner on the finer grid
    flat = _branch(56_943.0, 0.5, [56_940.0, 56_930.0], "subcritical")
    flat["stable"] = [False, True]
    up = _branch(57_097.0, 0.5, [57_100.0, 57_140.0], "supercritical") | {"grid": [192, 4]}
    flipped = cycle_errors(flat, up)
    assert flipped["errors"]["largest_stable_cycle_um"] == pytest.approx(math.sqrt(6.5))
    assert "supercritical on 192 θ cells" in flipped["text"]
