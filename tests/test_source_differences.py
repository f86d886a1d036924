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


# --- Eremyants (2.48)/(2.50), (2.53): the special four-bars' sign of ψ ----------------------------------

SCHEME_3 = {"l0": 4.0, "l1": 1.0, "l2": 3.0, "l3": 2.0, "assembly": 1, "limiter": 0}     # (λ₂, λ₃, λ₀) = (3, 2, 4)


def eremyants_2_48(phi, l2=4.0, l3=3.0, l0=2.0):
    """Scheme 1, ψ = π − arctan A₁ − arccos B₁ (B₁ with 2λ₃, as corrected), the textbook's frame: D = (λ₀, 0)."""
    d1 = 1 + l0**2 - 2 * l0 * np.cos(phi)
    return np.pi - np.arctan(np.sin(phi) / (l0 - np.cos(phi))) - np.arccos((l3**2 - l2**2 + d1) / (2 * l3 * np.sqrt(d1)))


def eremyants_2_50(phi, l2=3.0, l3=2.0, l0=4.0):
    """Scheme 3, ψ = −arctan A₂ + arccos B₂, the textbook's frame: D = (−λ₀, 0), the crank away from D at φ = 0."""
    d2 = 1 + l0**2 + 2 * l0 * np.cos(phi)
    return -np.arctan(np.sin(phi) / (l0 + np.cos(phi))) + np.arccos((l3**2 - l2**2 + d2) / (2 * l3 * np.sqrt(d2)))


def eremyants_2_53(phi, l2=3.0, l3=2.0, l0=4.0):
    s2, c = np.sin(phi / 2) ** 2, np.cos(phi / 2)
    return -(1 + l0 - 2 * l0 * s2 + (2 * l0 * s2 - l2 * (l0 + 1)) * c / np.sqrt(l2 * l3 / l0 - s2)) \
        / (1 + l0**2 + 2 * l0 * np.cos(phi))


def coupler_mismatch(pivot, rocker, psi, phi, coupler) -> float:
    """Largest |AC| − l₂ when the rocker's angle ψ is read counter-clockwise from +x: zero iff C = D + λ₃(cos ψ,
    sin ψ) closes the loop with the crank A = (cos φ, sin φ)."""
    c = np.asarray(pivot) + rocker * np.stack([np.cos(psi), np.sin(psi)], 1)
    return float(np.max(np.abs(np.hypot(c[:, 0] - np.cos(phi), c[:, 1] - np.sin(phi)) - coupler)))


def test_eremyants_2_50_counts_the_rocker_clockwise_and_2_48_counter_clockwise():
    """The exact geometry decides the convention: ψ of (2.48), read counter-clockwise, closes scheme 1's loop;
    ψ of (2.50) closes scheme 3's loop only read clockwise (counter-clockwise the coupler is off by up to 0.9 l₁).
    So the textbook's scheme-3 ψ runs against φ, and u₃₁ of (2.53) is minus the counter-clockwise rocker's."""
    phi = np.linspace(0.05, 2 * np.pi - 0.05, 60)
    assert coupler_mismatch((2.0, 0.0), 3.0, eremyants_2_48(phi), phi, 4.0) < 1e-12
    psi = eremyants_2_50(phi)
    assert coupler_mismatch((-4.0, 0.0), 2.0, -psi, phi, 3.0) < 1e-12
    assert coupler_mismatch((-4.0, 0.0), 2.0, psi, phi, 3.0) > 0.5


def test_scheme_3_u31_is_minus_2_53_by_finite_differences_of_the_exact_geometry():
    """θ = −ψ(2.50), the counter-clockwise rocker angle that closes the loop (test above), differentiated by central
    differences (h = 1e-5: error ~h²u‴ < 1e-8) is the app's u₃₁ at φ + π (its frame is the textbook's turned by
    180°, D at +l₀: a rotation keeps the sense of angles) and −(2.53); the issue's numbers included."""
    phi, h = np.linspace(0.05, 2 * np.pi - 0.05, 60), 1e-5
    theta_rate = -(eremyants_2_50(phi + h) - eremyants_2_50(phi - h)) / (2 * h)
    from server.core.mechanisms import MECHANISMS
    four_bar = MECHANISMS["four_bar"]
    p = four_bar.check(SCHEME_3)
    ours = four_bar.evaluate(p, phi + np.pi, set()).values["u31"]
    np.testing.assert_allclose(ours, theta_rate, atol=1e-8)
    np.testing.assert_allclose(ours, -eremyants_2_53(phi), atol=1e-12)
    issue = four_bar.evaluate(p, np.array([np.pi + 1e-7, 1.5 * np.pi, 2 * np.pi, 2.5 * np.pi, 3 * np.pi - 1e-7]),
                              set()).values["u31"]
    np.testing.assert_allclose(issue, [-0.28990, -0.39872, -0.33333, 0.51636, 0.68990], atol=5e-6)


@pytest.mark.parametrize("lang", LANGS)
def test_scheme_3_scene_shows_the_textbooks_sign_beside_ours(lang):
    """The scheme-3 variant says (2.50) counts ψ against φ and shows u₃₁ leaving (φ = 180°) and arriving
    (φ = 540°) with the app's sign and the textbook's, three decimals, computed here."""
    variant = next(v for v in scene_json("transfer_functions")["variants"] if v["id"] == "special_3")
    text = variant["text"][lang]
    assert "(2.50)" in text and "(2.53)" in text and "2.9" in text
    from server.core.mechanisms import MECHANISMS
    four_bar = MECHANISMS["four_bar"]
    ours = four_bar.evaluate(four_bar.check(SCHEME_3), np.array([np.pi + 1e-9, 3 * np.pi - 1e-9]), set()).values["u31"]
    book = eremyants_2_53(np.array([1e-9, 2 * np.pi - 1e-9]))
    comma = "," if lang != "en" else "."
    for here, printed in zip(ours, book):
        shown = [f"{v:+.3f}".replace("-", "−").replace(".", comma) for v in (here, printed)]
        assert shown[0] != shown[1] and all(s in text for s in shown), (shown, text)
        assert text.index(shown[0]) < text.index(shown[1])          # ours first, then the textbook's


# --- Chaika–Vasylenko Fig. 4.7: the maxima read from the figure ---------------------------------------

BOOK_REQUEST = {"reactions": "table_4_3", "I_pin": 6e-11, "I_bush": 1e-10, "I_piston": 2e-12, "I_cylinder": 3e-12,
                "hours": 1000, "outputs": ["wear"]}


@pytest.fixture(scope="module")
def book_wear():
    from server.api.endpoints import compute
    return compute("wear", BOOK_REQUEST)


def test_figure_4_7_maxima_shown_beside_ours_with_the_books_own_half(book_wear):
    """The /wear answer for the book's data carries Fig. 4.7's maxima (36, 68, 59 µm) beside its own largest
    wear (76.2, 134.5, 101.1 µm: the distributions' maxima) and the book's sums with its printed k over
    N_c/2 (38.9, 69.0, 58.8 µm, within 8 % of the figure).  By hand: the wear is linear in k and N_c, so the
    last column is ours × k_printed/k_ours / 2 (rel 1e-12)."""
    rows = {r["element"]: r for r in book_wear["figure_4_7"]}
    assert {k: r["figure"] for k, r in rows.items()} == {"pin_23": 36.0, "bush_23": 68.0, "cylinder_max": 59.0}
    assert rows["bush_23"]["table"] == pytest.approx(max(book_wear["bush"]), rel=1e-12)
    assert rows["pin_23"]["table"] == pytest.approx(max(book_wear["pin"]), rel=1e-12)
    assert rows["cylinder_max"]["table"] == pytest.approx(max(book_wear["cylinder"]), rel=1e-12)
    assert (rows["bush_23"]["table"], rows["cylinder_max"]["table"]) == (pytest.approx(134.5, abs=0.05),
                                                                         pytest.approx(101.1, abs=0.05))
    k = book_wear["coefficients"]
    printed = {"pin_23": ("pin", 0.68e-17), "bush_23": ("bush", 1.14e-17), "cylinder_max": ("cylinder", 1.41e-17)}
    for key, (part, k_printed) in printed.items():
        row = rows[key]
        assert row["book_half"] == pytest.approx(row["table"] * k_printed / k[part] / 2, rel=1e-12)
        assert abs(row["book_half"] / row["figure"] - 1) < 0.08
    assert [round(rows[key]["book_half"], 1) for key in ("pin_23", "bush_23", "cylinder_max")] == [38.9, 69.0, 58.8]


@pytest.mark.parametrize("lang", LANGS)
def test_wear_scene_shows_figure_4_7_with_the_reason(lang):
    """The Table 4.3 variant shows the panel; its note gives the three numbers of the last column and N_c."""
    scene = scene_json("wear")
    variant = next(v for v in scene["variants"] if v["id"] == "table_4_3")
    assert "figure_4_7" in variant["panels"]
    note = scene["panels"]["figure_4_7"]["note"][lang]
    numbers = ("38.9", "69.0", "58.8", "1.44·10⁸", "0.72·10⁸")
    for number in numbers:
        assert (number if lang == "en" else number.replace(".", ",")) in note
    words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
    assert "wear_element_cylinder_max" in words


# --- Chaika–Vasylenko (3.6), (3.7), (3.19), (3.27), (3.40): printed beside corrected ------------------------

@pytest.fixture(scope="module")
def central_forces():
    from server.api.endpoints import compute
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["forces-friction"]
    variant = next(v for v in scene.variants if v.id == "central")
    request = scene_request(scene, variant)
    return request, compute("forces", request)


def test_crank_slider_misprints_corrected_values_are_the_apps_own(central_forces):
    """Each corrected value against the app's kinetostatics of the same crank-slider (a route of its own: the
    joints' positions and the d'Alembert loads it solves with); the printed ones by hand.  The scene's crank-slider:
    l₁ = 0.1, l₂ = 0.4 (λ₂ = 4), S₂ at 0.3 of AB, ω = 50 rad/s, m₂ = 3 kg, ε₁ = 0."""
    from server.core.kinetostatics.crank_slider import analyse, Loads, Pairs
    from server.core.mechanisms import MECHANISMS
    request, answer = central_forces
    rows = {r["key"]: r for r in answer["errata"]}
    assert set(rows) == {"slider_acceleration_36", "rod_centre_acceleration_36", "rod_angle_37", "inertia_arm_319",
                         "relative_rate_327"}
    params = MECHANISMS["slider_crank"].check(request["params"])
    l1, l2, omega, m2, m3 = params["l1"], params["l2"], request["loads"]["omega"], request["loads"]["m2"], \
        request["loads"]["m3"]
    lam = l2 / l1
    phi = np.linspace(0, 2 * np.pi, 2881)
    loads = Loads(m2=m2, m3=m3, omega=omega, gravity=False)
    analysis = analyse(params, loads, Pairs(), phi, table=False)
    a, b, s2 = (analysis.points[k] for k in ("A", "B", "S2"))
    # (3.6) a_B: |F_in3|/m₃ (d'Alembert), largest at the dead centre l₁ω²(1 + 1/λ₂); printed l₁ω²(1 + 2/λ₂)
    slider = np.max(np.linalg.norm(analysis.applied["F_in3"], axis=1)) / m3
    assert rows["slider_acceleration_36"]["corrected_value"] == pytest.approx(slider, rel=1e-6)
    assert rows["slider_acceleration_36"]["printed_value"] == pytest.approx(l1 * omega**2 * (1 + 2 / lam), rel=1e-12)
    # (3.7): the rod's largest angle from the joints, arcsin(1/λ₂); printed 0 (λ_e = 0)
    rod = np.degrees(np.max(np.abs(np.arcsin((b[:, 1] - a[:, 1]) / l2))))
    assert rows["rod_angle_37"]["corrected_value"] == pytest.approx(rod, abs=1e-6)
    assert rows["rod_angle_37"]["printed_value"] == 0.0
    # (3.19): the moment of F_2in about A as the vector product, largest over the cycle (grids of 1441 and 2881
    # points: the maximum of a smooth curve to 1e-5)
    from server.core.kinetostatics.crank_slider import cross
    arm = np.max(np.abs(cross(s2 - a, analysis.applied["F_in2"])))
    assert rows["inertia_arm_319"]["corrected_value"] == pytest.approx(arm, rel=1e-5)
    assert rows["inertia_arm_319"]["printed_value"] != pytest.approx(arm, rel=1e-2)
    # (3.6) a_S2x at φ₁ = 45°: the component along the guide of S₂'s acceleration (F_in2/m₂) where the crank
    # makes 45° with the line from O to the slider (the book's φ₁; either sense: the central linkage is symmetric)
    o = analysis.points["O"]
    crank, guide = a - o, b - o
    angle = np.degrees(np.arccos(np.sum(crank * guide, 1) / np.linalg.norm(crank, axis=1)
                                 / np.linalg.norm(guide, axis=1)))
    i = int(np.argmin(np.abs(angle - 45.0)))
    assert angle[i] == pytest.approx(45.0, abs=1e-9)
    f_in2 = analysis.applied["F_in2"]
    along = abs(np.dot(f_in2[i], guide[i] / np.linalg.norm(guide[i]))) / m2
    assert abs(rows["rod_centre_acceleration_36"]["corrected_value"]) == pytest.approx(along, rel=1e-6)
    assert abs(rows["rod_centre_acceleration_36"]["printed_value"]) != pytest.approx(along, rel=1e-4)
    # (3.27) at φ₁ = 0: |1 − u₂₁| = 1 + 1/λ₂ (the rod turns against the crank there), printed 1 − 1/λ₂
    assert rows["relative_rate_327"]["corrected_value"] == pytest.approx(1 + 1 / lam, rel=1e-12)
    assert rows["relative_rate_327"]["printed_value"] == pytest.approx(1 - 1 / lam, rel=1e-12)
    rate = np.gradient(np.unwrap(np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])), phi)
    assert np.max(np.abs(1 - rate)) == pytest.approx(1 + 1 / lam, rel=1e-5)


def test_parallel_efficiency_as_printed_beside_corrected():
    """(3.40), two branches η = 0.9, 0.8 with A_P = 100, 300 J: corrected (90 + 240)/400 = 0.825, printed
    Σ η_k = 1.7 (by hand); series unchanged."""
    from server.api.endpoints import compute
    answer = compute("efficiency-chain", {"efficiencies": [0.9, 0.8], "works": [100, 300]})
    assert answer["parallel"] == pytest.approx(0.825, rel=1e-12)
    (row,) = answer["errata"]
    assert (row["key"], row["equation"]) == ("parallel_efficiency_340", "(3.40)")
    assert row["printed_value"] == pytest.approx(1.7, rel=1e-12)
    assert row["corrected_value"] == pytest.approx(0.825, rel=1e-12)


def test_new_errata_rows_have_their_words_in_three_languages(central_forces):
    from server.core import errata
    rows = [*central_forces[1]["errata"], errata.parallel_efficiency([0.5], [1.0])]
    for lang in LANGS:
        words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
        for r in rows:
            for name in (f"erratum_why_{r['key']}", f"erratum_printed_{r['key']}", f"erratum_corrected_{r['key']}",
                         f"erratum_unit_{r['unit']}", f"source_{r['source']}"):
                assert name in words, (lang, name)
        assert "chain_parallel_printed" in words
    scene = scene_json("forces_friction")
    assert "errata" in next(v for v in scene["variants"] if v["id"] == "central")["panels"]


# --- Lecture 10: the drilling rig's slips the flywheel study computes right ------------------------------

@pytest.fixture(scope="module")
def rig_flywheel():
    from server.api.endpoints import compute
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["flywheel"]
    variant = next(v for v in scene.variants if v.id == "rig")
    return compute("flywheel", scene_request(scene, variant))


def test_lecture10_rig_slips_beside_the_studys_own_numbers(rig_flywheel):
    """Step 1.3: I_v printed = group I (the crankshaft I₁₀ = 2.72 kg·m², the lecture's datum), corrected the cycle
    mean of I_II, 0.55079 kg·m² by the lecture's kinematics (L12)–(L14), (L18) (the notes' table: 5 digits);
    (L17): the driving work over the cycle, the answer's A_д(2π), and its negative; §10.6: b/(2π) = 38.197 mm/rad
    under either symbol; ω₁ср 47.124 in rad/s² as printed, rad/s corrected."""
    rows = {r["key"]: r for r in rig_flywheel["errata"]}
    groups = rows["groups_reversed"]
    assert groups["printed_value"] == pytest.approx(2.72, rel=1e-12)
    assert groups["printed_value"] == pytest.approx(rig_flywheel["group_i_existing"], rel=1e-12)
    assert groups["corrected_value"] == pytest.approx(0.55079, abs=5e-6)
    driving = rows["driving_ordinate"]
    assert driving["corrected_value"] == pytest.approx(rig_flywheel["curves"]["work_driving"][-1], rel=1e-12)
    assert driving["printed_value"] == -driving["corrected_value"] and driving["corrected_value"] > 0
    scale = rows["phi_scale"]
    assert scale["printed_value"] == scale["corrected_value"] == pytest.approx(240 / (2 * np.pi), rel=1e-12)
    assert (scale["printed_unit"], scale["unit"]) == ("mm_rad_as_pressure", "mm_rad")
    omega = rows["omega_unit"]
    assert omega["printed_value"] == omega["corrected_value"] == pytest.approx(47.124, rel=1e-12)
    assert (omega["printed_unit"], omega["unit"]) == ("rad_s2", "rad_s")
    for lang in LANGS:
        words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
        for r in rows.values():
            for name in (f"erratum_why_{r['key']}", f"erratum_printed_{r['key']}", f"erratum_corrected_{r['key']}",
                         f"erratum_unit_{r['unit']}", f"erratum_unit_{r['printed_unit']}"):
                assert name in words, (lang, name)


# --- Eremyants (3.34) beside (3.33) ------------------------------------------------------------------------

def test_viscous_moment_approximation_3_34_beside_the_exact_3_33():
    """The resisting-moment answer of the crank-slider carries M_T/(βω) by (3.33), the app's own u₃₁², and by
    (3.34) l₁² sin²φ(1 − cos φ/λ)².  Derivation (no number is printed): replacing √(λ² − sin²φ) by λ leaves
    an error O(λ⁻³) relative to l₁² (sin 2φ sin²φ/(4λ³) in u₃₁): checked as the relative difference 0.0118 at
    λ = 3 falling at least 25 times by λ = 10; at φ = 90° both are l₁² exactly (cos φ = 0, sin 2φ = 0)."""
    from server.api.endpoints import compute
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["resisting-moment"]
    variant = next(v for v in scene.variants if v.id == "slider_crank")
    assert "viscous" in variant.panels
    answer = compute("reduction", scene_request(scene, variant))
    shape = answer["resisting"]["viscous_shape"]
    from server.core.mechanisms import MECHANISMS
    mech = MECHANISMS["slider_crank"]
    p = mech.check(scene_request(scene, variant)["params"])
    phi = np.asarray(answer["phi"])
    u31 = mech.evaluate(p, phi, set()).values["u31"]
    np.testing.assert_allclose(shape["exact"], u31**2, rtol=0, atol=1e-14)
    lam = p["l2"] / p["l1"]
    np.testing.assert_allclose(shape["approximation"],
                               p["l1"] ** 2 * np.sin(phi) ** 2 * (1 - np.cos(phi) / lam) ** 2, atol=1e-15)
    quarter = int(np.argmin(np.abs(phi - np.pi / 2)))
    assert shape["approximation"][quarter] == pytest.approx(shape["exact"][quarter], abs=1e-12)
    from server.core.dynamics.report import slider_viscous_shape
    grid = np.linspace(0, 2 * np.pi, 4001)
    errors = [slider_viscous_shape({"l1": 1.0, "l2": lam, "e": 0.0}, grid)["largest_error"] for lam in (3.0, 10.0)]
    assert errors[0] == pytest.approx(0.0118, abs=5e-5)
    assert errors[0] / errors[1] > 25
    for lang in LANGS:
        assert "(3.34)" in scene_json("resisting_moment")["panels"]["viscous"]["title"][lang]


# --- Chaika–Vasylenko §1: the friction coefficients and the wear-resistance classes ------------------------

def test_section_1_reference_tables_as_printed_and_on_their_scenes():
    """The four ranges of f as printed (the first backwards, 0.8 … 0.6, with its note); ten classes 0…IX, class k
    the decade 10^(k−13)…10^(k−12), whose groups' upper ends are the printed 10⁻¹²…10⁻⁷ (0–V), 10⁻⁶…10⁻⁵
    (VI–VII), 10⁻⁴…10⁻³ (VIII–IX); each shown (written into its panel) on the wear and friction scenes."""
    from server.lessons.scenes import scenes
    every = scenes()
    friction = every["forces-friction"].panels["friction_coefficients"]
    assert [row["f"] for row in friction["rows"]] == [[0.8, 0.6], [0.4, 0.8], [0.1, 0.6], [0.0001, 0.02]]
    assert all(friction["rows"][0]["note"][lang] for lang in LANGS)
    classes = every["wear"].panels["wear_classes"]["rows"]
    assert [row["class"] for row in classes] == ["0", "I", "II", "III", "IV", "V", "VI", "VII", "VIII", "IX"]
    for k, row in enumerate(classes):
        assert row["I_s"] == pytest.approx([10.0 ** (k - 13), 10.0 ** (k - 12)], rel=1e-12)
    groups = [row["group"]["en"] for row in classes]
    assert len(set(groups[:6])) == len(set(groups[6:8])) == len(set(groups[8:])) == 1 == len({groups[5]} & {groups[6]}) + 1
    uppers = [row["I_s"][1] for row in classes]
    assert (uppers[0], uppers[5], uppers[6], uppers[7], uppers[8], uppers[9]) == pytest.approx(
        (1e-12, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3), rel=1e-12)
    for scene, variant, panel in (("wear", "engine", "wear_classes"), ("wear", "table_4_3", "wear_classes"),
                                  ("forces-friction", "central", "friction_coefficients")):
        assert panel in next(v for v in every[scene].variants if v.id == variant).panels


# --- Chaika–Vasylenko Table 4.4 row by row, N_c and a₂…a₄ ------------------------------------------------

def test_table_4_4_rows_are_what_the_wear_sums(book_wear):
    """Our integrands of each row, summed by the book's trapezoid over the 13 rows (Δφ = π/6) and multiplied by
    the answer's a, are the answer's wear at the book's points (rel 1e-12); the printed columns summed the same
    way give the notes' 3148 (bush) and 3166 (pin) (±1) and the piston's 76.1 µm with the printed a₃п = 0.261."""
    rows = book_wear["table_4_4"]
    assert [r["phi"] for r in rows] == pytest.approx(list(range(0, 361, 30)), abs=1e-9)
    a = {r["quantity"]: r["value"] for r in book_wear["book_coefficients"]}
    step = np.pi / 6
    trapezoid = lambda column: step * (sum(r[column] for r in rows) - (rows[0][column] + rows[-1][column]) / 2)
    points = book_wear["points"]
    assert a["a_2"] * trapezoid("bush") == pytest.approx(points["bush_23"], rel=1e-12)
    assert a["a_3"] * trapezoid("pin") == pytest.approx(points["pin_23"], rel=1e-12)
    assert a["a_{3p}"] * trapezoid("piston") == pytest.approx(points["piston"], rel=1e-12)
    assert trapezoid("bush_printed") == pytest.approx(3148, abs=1)
    assert trapezoid("pin_printed") == pytest.approx(3166, abs=1)
    assert 0.261 * trapezoid("piston_printed") == pytest.approx(76.1, abs=0.05)


def test_cycles_and_coefficients_printed_beside_ours(book_wear):
    """N_c = 60·2400·1000 = 1.44·10⁸ as printed; a by (4.13), (4.17), (4.18) from the answer's k by hand; the
    printed a₂ = 0.042, a₃ = 0.025, a₃п = 0.261, a₄ = 0.454 beside them."""
    rows = {r["quantity"]: r for r in book_wear["book_coefficients"]}
    assert rows["N_c"]["value"] == rows["N_c"]["printed"] == pytest.approx(1.44e8, rel=1e-12)
    k, n = book_wear["coefficients"], 1.44e8
    assert rows["a_2"]["value"] == pytest.approx(2e6 * k["bush"] * n / (np.pi * 0.025), rel=1e-12)
    assert rows["a_3"]["value"] == pytest.approx(2e6 * k["pin"] * n / (np.pi * 0.025), rel=1e-12)
    assert rows["a_{3p}"]["value"] == pytest.approx(4e6 * k["piston"] * n / (np.pi * 0.076 * 0.075), rel=1e-12)
    assert rows["a_4"]["value"] == pytest.approx(4e6 * k["cylinder"] * n / (np.pi * 0.076 * 0.075), rel=1e-12)
    assert [rows[q]["printed"] for q in ("a_2", "a_3", "a_{3p}", "a_4")] == [0.042, 0.025, 0.261, 0.454]
    variant = next(v for v in scene_json("wear")["variants"] if v["id"] == "table_4_3")
    assert {"table_4_4", "book_coefficients"} <= set(variant["panels"])


# --- Drakunov–Tuleshova: the four-bar's Grashof class on its page ----------------------------------------------

@pytest.mark.parametrize("lengths, cls, relation, shortest", [
    ((1.0, 0.3, 1.0, 0.8), "crank_rocker", "<", "l_1"),          # the scene's linkage: 1.3 < 1.8
    ((0.3, 1.0, 1.0, 0.8), "double_crank", "<", "l_0"),
    ((1.0, 0.8, 0.3, 1.0), "double_rocker", "<", "l_2"),
    ((4.0, 1.0, 3.0, 2.0), "change_point_linkage", "=", "l_1"),  # Eremyants' scheme 3: 1 + 4 = 3 + 2
    ((1.0, 0.9, 0.3, 0.35), "non_grashof", ">", "l_2"),
])
def test_grashof_row_by_hand(lengths, cls, relation, shortest):
    from server.core.mechanisms.four_bar import grashof_row
    row = grashof_row(*lengths)
    ordered = sorted(lengths)
    assert (row["class"], row["relation"], row["shortest"]) == (cls, relation, shortest)
    assert row["s_plus_l"] == pytest.approx(ordered[0] + ordered[3]) and row["p_plus_q"] == pytest.approx(
        ordered[1] + ordered[2])


def test_elastic_four_bar_page_shows_the_grashof_row():
    from server.api.endpoints import compute
    from server.lessons.requests import scene_request
    from server.lessons.scenes import scenes
    scene = scenes()["elastic-four-bar"]
    variant = scene.variants[0]
    assert "grashof" in variant.panels
    (row,) = compute("elastic", scene_request(scene, variant))["assemblies"]["grashof"]
    assert row == {"class": "crank_rocker", "s_plus_l": pytest.approx(1.3), "relation": "<",
                   "p_plus_q": pytest.approx(1.8), "shortest": "l_1"}
    for lang in LANGS:
        words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
        assert all(key in words for key in ("crank_rocker", "double_crank", "double_rocker", "change_point_linkage",
                                            "non_grashof"))


# --- Lecture 10's "(L…)" numbers explained on the pages that use them ---------------------------------------

@pytest.mark.parametrize("scene, shown", [("flywheel", True), ("induction-motor", True), ("flywheel-analysis", True),
                                          ("reduced-inertia", True), ("wear", False)])
def test_pages_with_lecture_numbers_say_they_are_the_apps(scene, shown):
    from fastapi.testclient import TestClient
    from server.api.app import app
    client = TestClient(app)
    for lang in LANGS:
        html = client.get(f"/scenes/{scene}?lang={lang}").text
        assert ('id="lecture-numbering"' in html) == shown, (scene, lang)
        if shown:
            words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
            assert words["lecture10_numbering"].split(" ")[0] in html


# --- Lecture 10: Merzalov's construction on the drawing sheet (L15)–(L24) -------------------------------------

def test_merzalov_sheet_scales_follow_the_lectures_relations(rig_flywheel):
    """μ_φ = 240/(2π); μ_p = 100 mm/4.4 MPa; μ_F = μ_p/S_п (d_п of the rig's indicator); μ_A = μ_M μ_φ/k₁ (L19);
    μ_T = 2μ_I/ω² (L20); ΔT_Imax = y_ΔTImax/μ_A and I_I = ΔT_Imax/(ω²[δ]) (L22), which is Merzalov's own I_I
    (rel 1e-5: the sheet takes the grid's extremes, the study refines them by a parabola); μ_ω = μ_A I_I ω (L24);
    μ_M, μ_I round (1, 2, 2.5, 4, 5 × 10ᵏ per mm read back) and their diagrams within 80 and 60 mm."""
    sheet = rig_flywheel["merzalov_sheet"]
    mu = {r["symbol"]: r["value"] for r in sheet["scales"]}
    omega, delta = 47.124, 1 / 80
    assert mu["μ_φ"] == pytest.approx(240 / (2 * np.pi), rel=1e-12)
    assert mu["μ_p"] == pytest.approx(100 / 4.4, rel=1e-6)              # mm per MPa
    assert mu["μ_A"] == pytest.approx(mu["μ_M"] * mu["μ_φ"] / mu["k_1"], rel=1e-12)
    assert mu["μ_T"] == pytest.approx(2 * mu["μ_I"] / omega**2, rel=1e-4)
    assert mu["ΔT_Imax"] == pytest.approx(mu["y_ΔTImax"] / mu["μ_A"], rel=1e-12)
    assert mu["I_I"] == pytest.approx(mu["ΔT_Imax"] / (omega**2 * delta), rel=1e-4)
    merzalov = next(m for m in rig_flywheel["methods"] if m["method"] == "merzalov")
    assert mu["I_I"] == pytest.approx(merzalov["inertia"], rel=1e-5)
    assert mu["μ_ω"] == pytest.approx(mu["μ_A"] * merzalov["inertia"] * omega, rel=1e-4)
    for name in ("μ_M", "μ_I"):
        per_mm = 1 / mu[name]
        mantissa = per_mm / 10 ** np.floor(np.log10(per_mm) + 1e-12)
        assert any(abs(mantissa - m) < 1e-9 for m in (1, 2, 2.5, 4, 5)), (name, per_mm)
    rows = sheet["ordinates"]
    assert [r["phi"] for r in rows] == pytest.approx(list(range(0, 361, 30)))
    assert max(abs(r["y_M"]) for r in rows) <= 80 and max(r["y_I"] for r in rows) <= 60
    for r in rows:
        assert r["y_A"] == pytest.approx(r["y_A_d"] + r["y_A_c"], abs=1e-9)
        assert r["y_TII_star"] == pytest.approx(r["y_I"] * mu["μ_A"] / mu["μ_T"], rel=1e-12)
    # y_ΔTI = y_A − y*_TII from the initial position (L21)
    first = rows[0]
    for r in rows:
        assert r["y_dTI"] == pytest.approx((r["y_A"] - r["y_TII_star"]) - (first["y_A"] - first["y_TII_star"]),
                                           abs=1e-6)
    for lang in LANGS:
        words = json.loads((CONTENT / "i18n" / f"{lang}.json").read_text("utf-8"))
        assert all(f"sheet_unit_{r['unit']}" in words for r in sheet["scales"])
    variant = next(v for v in scene_json("flywheel")["variants"] if v["id"] == "rig")
    assert {"merzalov_scales", "merzalov_ordinates"} <= set(variant["panels"])
