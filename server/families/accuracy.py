"""The slider family's accuracy and limits: the tolerance of its interpolation, the safety factors of its
error bounds, the members' count and spacing (server/families/family.py explains each)."""
from __future__ import annotations

import re



TOLERANCE = 0.005               # 0.5 % of a plotted quantity's span: below a plot's resolution
PREVIEW_FRACTION = 1 / 50       # a member's own error, at most this fraction of TOLERANCE (see Preview accuracy)
PREVIEW = PREVIEW_FRACTION * TOLERANCE   # … as a fraction of a drawn quantity's span: 1e-4
START_MEMBERS = 9
LEAN_MEMBERS = 5                # a coarse family while previews queue: the first 5 of the 9, every other one
MAX_MEMBERS = 65                # 8 intervals halved three times over the whole range, at most
FINEST_FRACTION = 1 / 1024      # an interval this narrow (of the range) is not halved: no slider resolves it
SIGNIFICANT = 5                 # significant digits of every float in the family's answer
ROUNDOFF = 1e-12                # below this fraction of its siblings' size a quantity's span is round-off
SAME_KIND = 1e-4                # ... or, inside one object, invisible beside its siblings (see spans)
# Not checked against the bound: how it was computed, the texts, and the reactions' directions in degrees (they
# wrap at ±180°, where no interpolation is right; the page draws the forces from their components).
# The successive approximations of an iteration (the forces' "iteration": changes 1e-1 … 1e-8; the textbook's
# "friction_iteration" at one crank angle: its steps and their limit) are a record of how it converged, read
# as a table and a sentence from the exact answer (readings_view.js), not curves a preview draws.
UNCHECKED = frozenset({"numerics", "study", "warnings", "directions", "iteration", "friction_iteration"})
# An interval is halved while its estimated error exceeds TOLERANCE / SAFETY. The estimate is exact for a
# parabola; for a corner (slopes s and s + Δs meeting inside the interval, at d from an end) the smaller of
# the ends' h²|f''|/8 is Δs·min(d, h − d)/8 against the true Δs·d(h − d)/h: at most 4× too small (d = h/2).
SAFETY = 4
# A cubic interval is halved while its estimate exceeds TOLERANCE / CUBIC_SAFETY. The estimate takes the fourth
# derivative from members around the interval, not inside it: where a curve has a corner inside (|R₃₄| of the
# forces' scene crossing zero as ω changes) it was measured 4.1× too small, and on the elastic transmission's
# motor speed 4.1× as well (0.517 % against a bound of 0.505 % at a factor 4): twice the linear rule's factor.
CUBIC_SAFETY = 8
PACK_QUANTUM = 1e-4            # a packed array's quantum, at most this fraction of its span (see Packed)
MAX_FIELDS = 64                 # dotted paths a family request may name (a scene's previews draw ~5–25)
FIELD = re.compile(r"[A-Za-z0-9_]{1,60}(\.[A-Za-z0-9_]{1,60}){0,7}")     # a dotted path of an answer's keys
COARSE_TO_FINE = (0, 8, 4, 2, 6, 1, 3, 5, 7)    # the order of the first 9 members
STAGES = ("coarse", "full")
