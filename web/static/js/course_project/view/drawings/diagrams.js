/**
 * The diagrams of the course project over the crank's turn (plot.js draws each): the output's position and
 * its first and second analogs s, s′, s″ (or θ, θ′, θ″ of a link) with the positions marked; the reduced moment
 * of inertia J(φ); the reduced resisting moment M_c(φ) with its parts and the constant driving moment M_d; the
 * works A_d, A_c, their difference ΔT and ΔT_I of group I; the crank's ω₁(φ) and ε₁(φ) with the flywheel. Every
 * ordinate at its own standard scale, written on it with μ_φ.
 */
import { formatQuantity } from "../../../common/view/notation.js";
import { heading } from "./captions.js";
import { Figure } from "./figure.js";
import { anglePlot, phiScaleText } from "./plot.js";

const HEAD = 18;               // mm of the heading
const GAP = 6;                 // mm between stacked diagrams

function stacked(title, className, plots, answer, t, lang, options) {
  const figure = new Figure();
  heading(figure, [0, 0], title, [phiScaleText(t, lang)]);
  let top = HEAD;
  for (const spec of plots) {
    top = anglePlot(figure, [0, top], { marks: answer.output_diagrams.marks, ...spec }, t, lang).bottom + GAP;
  }
  return options.figure ? figure : figure.toSvg(title, className);
}

/** The output's s(φ), s′(φ), s″(φ) (or θ, θ′, θ″) from answer.output_diagrams, the positions marked. */
export function outputDiagrams(answer, t, lang, options = {}) {
  const out = answer.output_diagrams;
  const symbol = out.quantity === "s" ? "s" : "θ";
  const unit = out.unit === "m" ? t.units_m : t.units_rad;
  const analogUnit = out.unit === "m" ? t.units_m : "";        // θ′ and θ″ are dimensionless
  return stacked(t.project_dwg_output_diagrams, "cp-output-diagrams", [
    { phi: out.phi, curves: [{ values: out.s, name: "s" }], symbol, unit, muSymbol: `μ_${symbol}` },
    { phi: out.phi, curves: [{ values: out.s1, name: "s1" }], symbol: `${symbol}′`, unit: analogUnit, muSymbol: `μ_{${symbol}′}` },
    { phi: out.phi, curves: [{ values: out.s2, name: "s2" }], symbol: `${symbol}″`, unit: analogUnit, muSymbol: `μ_{${symbol}″}` },
  ], answer, t, lang, options);
}

/** The reduced moment of inertia J(φ) of answer.dynamics. */
export function inertiaDiagram(answer, t, lang, options = {}) {
  const { dynamics: d } = answer;
  return stacked(t.project_dwg_inertia, "cp-inertia-diagram", [
    { phi: d.phi, curves: [{ values: d.J, name: "J" }], symbol: "J", unit: t.units_kg_m2, muSymbol: "μ_J" },
  ], answer, t, lang, options);
}

/** A part of M_c as written beside its curve: "force E/ram" → P_{E/ram}, "moment 5" → M_{5}, "gravity" → G. */
function partSymbol(name, t) {
  const [kind, ...rest] = name.split(" ");
  const what = rest.join(" ");
  if (kind === "force") return `P_{${what}}`;
  if (kind === "moment") return `M_{${what}}`;
  if (kind === "gravity") return "G";
  if (kind === "friction") return t.project_dwg_friction;
  return name;
}

/** M_c(φ) (main line) with each part (thin) and the constant driving moment M_d (dashed). */
export function momentsDiagram(answer, t, lang, options = {}) {
  const { dynamics: d } = answer;
  const Mc = t.project_dwg_symbol_Mc;
  const parts = Object.entries(d.M_c_parts ?? {});
  const curves = [{ values: d.M_c, label: Mc, name: "M_c" },
    ...(parts.length > 1 ? parts.map(([name, values]) => ({ values, label: `${Mc}: ${partSymbol(name, t)}`, kind: "thin", name })) : []),
    { values: d.phi.map(() => d.driving_moment), label: t.project_dwg_symbol_Md, kind: "dashed", name: "M_d", atEnd: true }];
  return stacked(t.project_dwg_moments, "cp-moments-diagram", [
    { phi: d.phi, curves, symbol: `${Mc}, ${t.project_dwg_symbol_Md}`, unit: t.units_N_m, muSymbol: "μ_M" },
  ], answer, t, lang, options);
}

/** The works A_d, A_c (thin), ΔT = A_d − A_c (main) and ΔT_I (dashed) over the turn. */
export function worksDiagram(answer, t, lang, options = {}) {
  const { dynamics: d } = answer;
  const curves = [
    { values: d.works.driving, label: t.project_dwg_symbol_Ad, kind: "thin", name: "A_d" },
    { values: d.works.resisting, label: t.project_dwg_symbol_Ac, kind: "thin", name: "A_c" },
    { values: d.works.total, label: "ΔT", name: "delta_T" },
    { values: d.delta_T, label: "ΔT_I", kind: "dashed", name: "delta_T_I" }];
  return stacked(t.project_dwg_works, "cp-works-diagram", [
    { phi: d.phi, curves, symbol: `${t.project_dwg_symbol_Ad}, ${t.project_dwg_symbol_Ac}, ΔT`, unit: t.units_J, muSymbol: "μ_A" },
  ], answer, t, lang, options);
}

/** The crank's ω₁(φ) with ω_max, ω_min and ω_m written, and ε₁(φ), with the flywheel. */
export function speedDiagram(answer, t, lang, options = {}) {
  const { dynamics: d } = answer;
  const mean = d.omega_mean;
  const line = (value, label, name) => ({ values: d.phi.map(() => value), label, kind: "dashed", name, atEnd: true });
  const w = (value) => `${formatQuantity(value, lang, 4)} ${t.units_rad_s}`;
  return stacked(t.project_dwg_speed, "cp-speed-diagram", [
    { phi: d.phi, curves: [{ values: d.omega, name: "omega" },
      line(d.omega_max.omega, `ω_max = ${w(d.omega_max.omega)}`, "omega_max"),
      line(d.omega_min.omega, `ω_min = ${w(d.omega_min.omega)}`, "omega_min"),
      line(mean, `${t.symbol_mean_speed} = ${w(mean)}`, "omega_mean")],
    symbol: "ω_1", unit: t.units_rad_s, muSymbol: "μ_ω", zero: false },
    { phi: d.phi, curves: [{ values: d.epsilon, name: "epsilon" }], symbol: "ε_1", unit: t.units_rad_s2, muSymbol: "μ_ε" },
  ], answer, t, lang, options);
}
