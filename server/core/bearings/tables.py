"""Allowable operating parameters of bearing materials: Chaika–Vasylenko Table 2.1 (dry friction, with the
friction coefficient f) and Table 2.2 (semi-fluid and fluid friction), as printed, converted to SI.

Each allowable is the printed range (low, high); a value printed once is (v, v); a cell printed "–" is None.
The designer checks against the LOW end of each allowable range (the side that is safe whatever the
supplier's grade) and heats the bearing with the HIGH end of the range of f (the more friction, the hotter):
both choices are ours, the book gives ranges only.  Doubtful cells are kept as printed and marked:
the OCR of Table 2.2 prints [p_mV] = 3 MPa·m/s for babbit Б16 (kept) and [p_m] = "0…2,5" MPa for nylon Б
(read as 2,0…2,5: a zero allowable pressure carries nothing).
"""
from __future__ import annotations

from dataclasses import dataclass

MPA = 1e6


@dataclass(frozen=True)
class Material:
    """One row: allowable mean pressure (Pa), sliding speed (m/s), pV (Pa·m/s), temperature (°C), and f."""

    key: str
    name: str                                   # the designation as printed (Russian/Ukrainian grade names)
    pressure: tuple[float, float]
    speed: tuple[float, float]
    pv: tuple[float, float] | None
    temperature: tuple[float, float] | None
    friction: tuple[float, float] | None = None

    def allowable(self) -> dict:
        """The values the checks use: low ends of the allowables, high end of f (None where the table is blank)."""
        low = lambda cell: None if cell is None else cell[0]
        return {"pressure": self.pressure[0], "speed": self.speed[0], "pv": low(self.pv),
                "temperature": low(self.temperature),
                "friction": None if self.friction is None else self.friction[1]}


def _row(key, name, p, v, pv, t, f=None) -> Material:
    pair = lambda cell, scale=1.0: None if cell is None else (
        (cell[0] * scale, cell[1] * scale) if isinstance(cell, tuple) else (cell * scale, cell * scale))
    return Material(key, name, pair(p, MPA), pair(v), pair(pv, MPA), pair(t), pair(f))


# Table 2.1: dry-friction bearings (ПСТ)
DRY = {m.key: m for m in (
    _row("bronze_brof", "БрОФ 6,5-0,15", (5, 20), 1.1, (25, 35), (70, 80), (0.12, 0.20)),
    _row("graphite", "графит", (0.3, 0.5), 1.5, 1.0, 400, (0.07, 0.10)),
    _row("graphite_metal", "графит, пропитанный металлом", (0.3, 1.0), 3.0, 1.5, (200, 300), (0.01, 0.05)),
    _row("carbon_plastic", "АМС-1, АФ-3Т", 0.5, (1.5, 2.0), 1.5, 200, (0.01, 0.05)),
    _row("nylon", "капрон", (1.5, 2.5), 0.2, (0.07, 0.10), (80, 90)),
    _row("nylon_am2", "капрон с наполнителем АМ-2", (2.0, 2.5), (2.5, 3.0), 3.5, 140),
    _row("cermet", "металлокерамика", 0.5, 2.0, 1.0, 500, (0.04, 0.16)),
    _row("cermet_hard", "металлокерамические твёрдые сплавы", 30, 15, (1.0, 1.5), 300, (0.11, 0.14)),
    _row("cermet_oil", "металлокерамика, пропитанная маслом", (18, 25), (4, 6), (0.7, 1.0), (70, 80), (0.04, 0.12)),
    _row("polyamide_ak7_dry", "полиамид АК-7, П-68", (2, 3), 0.5, (0.10, 0.15), 75, (0.12, 0.35)),
    _row("textolite_dry", "текстолит", 5.0, 1.0, 1.0, 80, (0.06, 0.15)),
)}

# Table 2.2: semi-fluid and fluid friction bearings
LUBRICATED = {m.key: m for m in (
    _row("bronze_brs30", "БрС30", 25, 12, 38, None),
    _row("bronze_bro10f1", "БрО10Ф1", 15, 10, 15, None),
    _row("bronze_bra9zh4l", "БрА9Ж4Л", 15, 4, 12, None),
    _row("babbit_b83", "Б83", (10, 15), 50, (50, 75), 115),
    _row("babbit_b16", "Б16", 10, 30, 3, 110),
    _row("nylon_b", "капрон Б", (2.0, 2.5), 5, 20, 100),      # printed "0…2,5"
    _row("brass_lks", "ЛКС 80-3-3", 12, 2, 10, None),
    _row("brass_lmtszh", "ЛМцЖ 52-4-1", 4, 2, 6, None),
    _row("polyamide_ak7", "полиамид АК-7", (15, 20), 4, 20, 100),
    _row("textolite_oil", "текстолит со смазкой маслом", 10, (5, 10), 25, 100),
    _row("ptfe", "фторопласт-4", 1.5, 5, None, 200),
    _row("ptfe_filled", "фторопласт-4 с наполнителем", (3.5, 4.0), (8, 10), None, 200),
    _row("iron_achs1", "АЧС-1", 2.5, 5, 10, None),
    _row("iron_achs5", "АЧС-5", 20, 1, 20, None),
)}

TABLES = {"dry": DRY, "semi_fluid": LUBRICATED, "fluid": LUBRICATED}

# Radial clearance h₀ = (D − d)/2 as a fraction of d: dry §2.2, semi-fluid §2.3 (usual, then "rarer");
# the book gives no range for fluid bearings.
CLEARANCE = {"dry": ((0.0005, 0.0020), None), "semi_fluid": ((0.00025, 0.0005), (0.0005, 0.001)), "fluid": None}

# Recommended journal diameters of a crank-slider as fractions of the cylinder bore D_p (§2.1).
JOURNAL_DIAMETER = {"O": (0.35, 0.65), "A": (0.23, 0.60), "B": (0.15, 0.30)}

# Relative length l̄_z = l_z/d recommended: dry 0.8…2.0 (§2.2), semi-fluid at most 1.2 (§2.3).
LENGTH_RATIO = {"dry": (0.8, 2.0), "semi_fluid": (0.0, 1.2), "fluid": None}


def material(kind: str, key: str) -> Material:
    """The row ``key`` of the table of bearings of ``kind``; KeyError if that table has no such row."""
    return TABLES[kind][key]
