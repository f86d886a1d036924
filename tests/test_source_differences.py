"""Where the app and the sources differ, the difference is shown and explained, never silent: the harmonics
note's sign (Eremyants (2.17)), the sign convention of Eremyants (2.50)/(2.53) (scheme 3 of the special
four-bars), Chaika–Vasylenko Fig. 4.7's maxima beside the /wear answer.  Each check against the app's own
computation or a derivation stated in the test."""
from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from server.core.kinematics import compute_kinematics

CONTENT = Path(__file__).parents[1] / "content"
LANGS = ("ru", "uk", "en")


def scene_json(name: str) -> dict:
    return json.loads((CONTENT / "scenes" / f"{name}.json").read_text("utf-8"))


def sign_of(text: str, term: str) -> int:
    """The sign written before ``term`` in ``text`` (+1 or −1); the term must occur once with a sign."""
    found = re.findall(r"([+−-])\s*" + re.escape(term), text)
    assert len(found) == 1, (term, text)
    return -1 if found[0] in "−-" else 1


# --- Eremyants (2.17): the 4φ harmonic of u′₃₁ ----------------------------------------------------------

@pytest.mark.parametrize("lang", LANGS)
def test_harmonics_note_gives_the_signs_of_the_panels_own_fft(lang):
    """The note of the panel harmonics_du31 names the 4φ terms of x (the slider's position s) and of u′₃₁ = s″.
    The signs written must be those of the cos 4φ coefficients of the FFT the panel itself draws (λ = 3:
    u′₃₁ +0.0101, s −0.00063), and u′₃₁'s term is s's times −(4²) (the second derivative of cos 4φ)."""
    note = scene_json("transfer_functions")["panels"]["harmonics_du31"]["note"][lang]
    spectrum = compute_kinematics("slider_crank", {"l1": 1.0, "l2": 3.0}, ["harmonics_du31"], n=3) \
        .outputs["harmonics_du31"]
    du31_cos4 = spectrum["cos"][3]
    assert du31_cos4 == pytest.approx(0.0101, abs=5e-5)
    assert sign_of(note, "l₁cos 4φ/(4λ³)") == np.sign(du31_cos4) == 1
    from server.core.mechanisms import MECHANISMS
    mech = MECHANISMS["slider_crank"]
    p = mech.check({"l1": 1.0, "l2": 3.0})
    phi = np.arange(1024) * 2 * np.pi / 1024
    s_cos4 = 2 * np.fft.rfft(mech.evaluate(p, phi, set()).values["s"]).real[4] / 1024
    assert sign_of(note, "l₁cos 4φ/(64λ³)") == np.sign(s_cos4) == -1
    assert du31_cos4 == pytest.approx(-16 * s_cos4, rel=1e-9)


def test_the_4phi_term_tends_to_the_notes_coefficient_for_a_long_rod():
    """+l₁/(4λ³) is the leading term of u′₃₁'s cos 4φ coefficient: at λ = 10 the FFT agrees to 1 % (the next
    term is O(λ⁻⁵))."""
    lam = 10.0
    cos4 = compute_kinematics("slider_crank", {"l1": 1.0, "l2": lam}, ["harmonics_du31"], n=3) \
        .outputs["harmonics_du31"]["cos"][3]
    assert cos4 == pytest.approx(1 / (4 * lam**3), rel=0.01)
