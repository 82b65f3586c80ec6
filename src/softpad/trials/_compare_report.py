"""A comparison of planner/detector pairs (:func:`softpad.trials.compare`) named, tabulated and
drawn: the pairs parsed from ``PLANNER:DETECTOR`` text, the Markdown table, the per-object
figure."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from softpad.errors import InputError


def parse_pairs(texts: Sequence[str] | None) -> list[tuple[str, str]]:
    """``PLANNER:DETECTOR`` texts as pairs of registered names.

    Parameters
    ----------
    texts
        ``"gripper-aware:adaptive"``, ...; None or empty: :data:`DEFAULT_PAIRS`.

    Returns
    -------
    list of tuple
        (planner, contact detector) names.
    """
    from softpad.planning import available_planners
    from softpad.sensing import available_contact_detectors
    from softpad.trials._compare import DEFAULT_PAIRS

    if not texts:
        return list(DEFAULT_PAIRS)
    planners, detectors = available_planners(), available_contact_detectors()
    out = []
    for text in texts:
        planner, _, detector = text.partition(":")
        if planner not in planners or detector not in detectors:
            raise InputError(
                f"--pair must be PLANNER:DETECTOR with PLANNER in {', '.join(planners)} and "
                f"DETECTOR in {', '.join(detectors)}, got {text!r}"
            )
        out.append((planner, detector))
    return out


def _pct(x: float | None) -> str:
    return "-" if x is None else f"{100 * x:.1f} %"


def comparison_table(comparison: dict[str, Any]) -> str:
    """One Markdown row per pair: success with its 95 % interval, contact delay, finger
    travel, false alarms per hour and failures; then, when the comparison has them, each
    pair against an earlier one (trial-level and object-level tests).

    Parameters
    ----------
    comparison
        What :func:`softpad.trials.compare` (or :func:`merge_comparisons`) returns.

    Returns
    -------
    str
        The seeds line and the table.
    """
    seeds = comparison["seeds"]
    lines = [
        f"seeds {seeds[0]}..{seeds[-1]} ({len(seeds)})",
        "| planner | detector | success | 95 % interval | delay median / p95 (ms) "
        "| travel median (mm) | false alarms/h | failures |",
        "|---|---|---:|---|---|---:|---:|---|",
    ]
    for c in comparison["combinations"]:
        lo, hi = c["success_interval"]
        dm, dp = c["delay_s_median"], c["delay_s_p95"]
        delay = "-" if dm is None else f"{1e3 * dm:.0f} / {1e3 * dp:.0f}"
        tm = c["finger_travel_m_median"]
        travel = "-" if tm is None else f"{1e3 * tm:.2f}"
        lines.append(
            f"| {c['planner']} | {c['detector']} | {c['successes']}/{c['trials']} = "
            f"{_pct(c['success'])} | {_pct(lo)} .. {_pct(hi)} | {delay} | {travel} | "
            f"{c['false_alarms_per_hour']:g} | {c['failures'] or '-'} |"
        )
    return "\n".join(
        lines
        + _recognition_lines(comparison["combinations"])
        + _contrast_table(comparison.get("contrasts", []))
    )


def _recognition_lines(combos: list[dict[str, Any]]) -> list[str]:
    """For each catalogue pair (one whose trials were recognised or handed on): how many
    trials it recognised as a known object and how many it called unknown."""
    lines = []
    for c in combos:
        known = sum(c.get("recognised_as", {}).values())
        unknown = c.get("unknown", 0)
        if known or unknown:
            lines.append(
                f"{c['planner']}:{c['detector']}: {known} trials recognised as a known object, "
                f"{unknown} called unknown (handed on), of {c['trials']}"
            )
    return ["", *lines] if lines else []


def _contrast_table(contrasts: list[dict[str, Any]]) -> list[str]:
    """Each pair against an earlier one: trials as independent, then objects as the unit."""
    if not contrasts:
        return []
    lines = [
        "",
        "| B against A | difference | trial-level p (Fisher) | objects better / worse "
        "| object-level p (sign-flip) | cluster bootstrap 95 % |",
        "|---|---:|---:|---|---:|---|",
    ]
    for c in contrasts:
        lo, hi = c["object_interval"]
        lines.append(
            f"| {c['b']} against {c['a']} | {100 * c['difference']:+.1f} points | "
            f"{c['trial_p_value']:.3g} | {c['objects_better']} / {c['objects_worse']} "
            f"of {c['objects']} | {c['object_p_value']:.3g} | "
            f"{100 * lo:+.1f} .. {100 * hi:+.1f} points |"
        )
    return lines


def plot_comparison(comparison: dict[str, Any]) -> Any:
    """Each object's success rate per pair, with its 95 % Wilson interval as whiskers.

    Parameters
    ----------
    comparison
        What :func:`softpad.trials.compare` returns.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (built without pyplot: no global backend, no window).
    """
    from matplotlib.figure import Figure

    combos = comparison["combinations"]
    names = [o["name"] for o in combos[0]["objects"]]
    fig = Figure(figsize=(11, 4))
    ax = fig.subplots()
    width = 0.8 / len(combos)
    for i, c in enumerate(combos):
        rates = [o["success"] for o in c["objects"]]
        lo = [r - o["success_interval"][0] for r, o in zip(rates, c["objects"], strict=True)]
        hi = [o["success_interval"][1] - r for r, o in zip(rates, c["objects"], strict=True)]
        xs = [k + i * width for k in range(len(names))]
        label = f"{c['planner']} + {c['detector']}: {_pct(c['success'])} overall"
        ax.bar(xs, rates, width, yerr=[lo, hi], capsize=2, label=label)
    ax.set_xticks([k + 0.4 - width / 2 for k in range(len(names))], names, rotation=30)
    ax.set_ylabel("success rate (95 % interval)")
    ax.set_ylim(0, 1.05)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    trials = combos[0]["trials"]
    ax.set_title(f"Experiment 2 over {len(comparison['seeds'])} seeds ({trials} trials a pair)")
    fig.tight_layout()
    return fig


__all__ = ["comparison_table", "parse_pairs", "plot_comparison"]
