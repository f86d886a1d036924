"""Where a question's answer shows on the public pages: a scene opened at the student's values (the
student's own address carries them) draws every panel of its variant, whatever an assignment hides on the
student's page. Derived from the scenes' data alone: a panel shows a question's answer when its outputs (or
the parts of the answer it needs) meet the question's ``hides``."""
from __future__ import annotations

from ..lessons.scenes import Question, Scene, Variant, scenes


def shows_any(panel: dict, outputs: set[str]) -> bool:
    """Whether a panel (its outputs, or the parts of the answer it needs) shows one of `outputs`."""
    return bool(outputs & set(panel.get("outputs", []) + panel.get("needs", [])))


def public_views(scene: Scene, variant: Variant, asked: Question) -> list[tuple[Scene, str, bool]]:
    """Where the public pages show a question's answer at the student's values: every panel of this variant,
    and of any other scene's variant of the same mechanism on the same endpoint with the same sliders (so it
    opens at the same values), whose outputs meet the question's ``hides``. Each as (scene, panel, direct):
    direct when the panel draws an output the answer is read from, else it lets the answer be derived."""
    hides, shown = set(asked.hides), []
    read = {name for readout in asked.readout_list() for name in readout.outputs}
    sliders = {s.id for s in variant.sliders}
    for other in scenes().values():
        if other.endpoint != scene.endpoint or other.kind != scene.kind:
            continue
        for same in other.variants:
            if other.id == scene.id and same.id != variant.id:
                continue
            if other.id != scene.id and (same.mechanism != variant.mechanism
                                         or not sliders <= {s.id for s in same.sliders}):
                continue
            shown += [(other, p, shows_any(other.panels.get(p, {}), read)) for p in same.panels
                      if shows_any(other.panels.get(p, {}), hides)]
    return shown
