"""The catalogue of validation cases (:data:`CASES`), in the order ``validate`` runs them.
"""

from __future__ import annotations

from ..core import Case
from ..recovery import (
    COVERAGE_MIN,
    Z_LIMIT,
)
from .common import LAWS_MD, THESIS
from .fe import _case_abaqus, _case_lsdyna, _case_radioss
from .laws import (
    _case_burckhardt,
    _case_documented_values,
    _case_identifiability,
    _case_pacejka,
    _case_recovery,
    _case_reference,
    _case_sliding_identities,
    _case_slip_peaks,
)
from .temperature import _case_wlf_pyvisco, _case_wlf_sets
from .thesis_tables import _case_mf52, _case_rig_units, _case_tyre, _thesis_poly_case

__all__ = ["CASES"]


CASES: tuple[Case, ...] = (
    Case("reference-implementations",
         "Every registered law against an independent reference implementation",
         LAWS_MD + "; thesis Eqs. 5-1/5-2 with Tables 5-1/5-2 (forms re-implemented by hand "
         "in frictionlaws/validation/reference.py, evaluated with mpmath at 40 digits)",
         "law value vs reference at every reference point (parameter sets x variable grid); "
         "tolerance: double round-off (1e-12 + 1e-9 relative); completeness: every built-in "
         "law must have a reference", _case_reference),
    Case("documented-settings-presets",
         "Fixed settings and published presets as documented",
         LAWS_MD + " (p_ref, F_ref, p0, WLF constants; Pacejka and Burckhardt presets); "
         "thesis Tables 5-1 and 5-2 (polynomial presets)",
         "each documented value equals the law's setting or preset value (exact, as typed)",
         _case_documented_values),
    Case("burckhardt-presets", "Burckhardt road presets: peak slip, peak mu, mu at s = 1",
         LAWS_MD + ", Burckhardt row (presets S: Burckhardt 1993 via several independent "
         "sources; derived peaks I)",
         "numerical maximum of the law over s = 0..1 vs the printed figures (tolerance half "
         "a unit of the last printed digit) and vs the closed form ln(c1 c2/c3)/c2",
         _case_burckhardt),
    Case("pacejka-presets", "Pacejka presets: peak slip, peak mu, slope at origin B C D",
         LAWS_MD + ", Pacejka row (MathWorks generic Magic Formula coefficients; derived "
         "peaks I); Pacejka, Tire and Vehicle Dynamics (B C D = slope at the origin)",
         "numerical maximum and central-difference slope of the law vs the printed figures "
         "(half a unit of the last digit) and vs an independent root of the peak condition",
         _case_pacejka),
    Case("slip-law-peaks", "Closed-form peaks of the rational and square-root slip laws",
         LAWS_MD + ", burckhardt-sqrt, kiencke-daiss and germann rows (I)",
         "numerical maximum of the law vs the closed forms; slopes at the origin",
         _case_slip_peaks),
    Case("exponential-decay-abaqus", "exponential-decay with delta = 1 vs Abaqus EXPONENTIAL "
         "DECAY", "Abaqus Analysis User's Guide, *FRICTION, EXPONENTIAL DECAY (fe-formats.md, "
         "C): mu = mu_k + (mu_s - mu_k) exp(-d_c slip rate)",
         "the manual's formula re-implemented with math.exp vs the law with v_c = 1/d_c, "
         "on 31 slip rates and 3 parameter sets; the card written by frictionlaws.export "
         "(SI and mm-N-s) read back and evaluated with the manual's formula; round-off",
         _case_abaqus),
    Case("exponential-decay-lsdyna", "exponential-decay with delta = 1 vs LS-DYNA FS/FD/DC",
         "LS-DYNA Keyword User's Manual, *CONTACT card 2 (fe-formats.md, C): "
         "mu = FD + (FS - FD) exp(-DC |v_rel|)",
         "the manual's formula vs the law with v_c = 1/DC, both velocity signs (round-off); "
         "card 2 written by frictionlaws.export read back by its 10-column fields (1e-7)",
         _case_lsdyna),
    Case("quadratic-pv-radioss", "quadratic-pv vs OpenRadioss Ifric = 1",
         "OpenRadioss /FRICTION and /INTER/TYPE7, Ifric = 1 generalized viscous law "
         "(fe-formats.md, C, from its source): mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + "
         "C5 v^2; Ifric = 4: mu = C1 + (Fric - C1) exp(-C2 v)",
         "the Radioss formula vs the law with c0 = Fric, c1..c5 = C1..C5 on a 13 x 10 (p, v) "
         "grid; the /FRICTION cards written by frictionlaws.export (Ifric 1 in SI and "
         "mm-N-s, Ifric 4 for exponential-decay) read back; round-off", _case_radioss),
    Case("wlf-constant-sets", "The two WLF constant sets are one function shifted by 50 K",
         "thesis Eq. 2-4 and laws.md: Grosch C1 = 8.86, C2 = 101.6 K at T_g + 50 K; "
         "Williams-Landel-Ferry (1955) C1 = 17.44, C2 = 51.6 K at T_g",
         "re-referencing the universal set by +50 K (C2' = C2 + 50, C1' = C1 C2/C2') gives "
         "Grosch's set within the rounding of the printed constants; log aT curves agree "
         "on T_g .. T_g + 100 K within the effect of that rounding", _case_wlf_sets),
    Case("wlf-fit-pyvisco", "WLF fitted to the pyvisco DMA shift factors",
         "NREL pyvisco example data (BSD-3-Clause): freq_user_master__shift_factors.csv, 21 "
         "shift factors -50..100 degC (datasets/dma-pyvisco)",
         "frictionlaws.viscoelastic.mastercurve.fit_wlf vs an independent scipy least-squares "
         "fit of the WLF equation written here (C1, C2, rms to 1e-4 relative)", _case_wlf_pyvisco),
    Case("thesis-poly2-steel", "Thesis Eq. 5-1 (Table 5-1, steel) on the 19 measured rows",
         THESIS + ", Eq. 5-1, Table 5-1, Figure 5-16a",
         "law evaluation = exact rational hand computation of the printed coefficients "
         "(1e-11); packaged rows = printed rows; residuals and R^2 reported, not asserted",
         _thesis_poly_case(2)),
    Case("thesis-poly3-steel", "Thesis Eq. 5-2 (Table 5-2, steel) on the 19 measured rows",
         THESIS + ", Eq. 5-2, Table 5-2, Figure 5-16a",
         "law evaluation = exact rational hand computation of the printed coefficients "
         "(1e-11); residuals and R^2 reported, not asserted", _thesis_poly_case(3)),
    Case("thesis-rig-units", "Thesis rig conversions: dead weights, pin area, pressures",
         THESIS + ", chapters 3-4 (1 kg -> 9.8 N -> 0.03119 MPa; 314.16 mm^2; design sizing "
         "57.12 N, 4.57 N m)", "pint-based unit handling and load_dataset(area=) vs the "
         "printed figures (half a unit of the last printed digit)", _case_rig_units),
    Case("sliding-law-identities", "Limits, peaks and identities stated in the catalogue",
         LAWS_MD + ", notes of thirion, denny, schallamach, savkoor, wriggers, huemer, park, "
         "nackenhorst (I)", "the law's values at limits and numerical peaks vs the stated "
         "closed forms", _case_sliding_identities),
    Case("identifiability-claims", "Over-parametrised published forms are reported",
         LAWS_MD + ", 'Identifiability' section and the denny / nackenhorst rows (I)",
         "the fitter names the parameters laws.md says cannot be told apart, and none for "
         "the identifiable 5-parameter Nackenhorst form", _case_identifiability),
    Case("parameter-recovery", "Parameter recovery for every law across noise and sample size",
         "synthetic data from the independent reference implementations (reference.py) at "
         "known parameters", f"|z| = |estimate - truth|/stderr <= {Z_LIMIT:g} at the lowest "
         f"noise; fitted curve within 1.5 noise sigma of the truth; coverage of the 95 % "
         f"intervals >= {COVERAGE_MIN:.2f} per noise level and sample size", _case_recovery),
    Case("mf52-fx0", "Magic Formula 5.2 pure longitudinal force vs the published equations",
         "Pacejka, Tire and Vehicle Dynamics (2006) eqs. 4.E9-4.E19 as written in laws.md; "
         "coefficients: Project Chrono MagicFormula52 example (BSD-3-Clause, not measured)",
         "F_x0 re-implemented by hand from the equations vs frictionlaws.tyre.MagicFormula "
         "at 4 loads x 7 slips (tolerance 1e-9 F_z); peak mu_x = PDX1 + PDX2 dfz",
         _case_mf52),
    Case("tyre-table-6-2", "The thesis' tyre conclusion with the brush model",
         THESIS + ", chapter 6, Table 6-2 (cornering stiffness of the FE tyre, 2..6.5 kN); "
         "brush model: Pacejka, Tire and Vehicle Dynamics, ch. 3",
         "constant-mu brush tyre vs its closed form; CS(6.5 kN)/CS(2 kN) with a law fitted to "
         "thesis-steel at most 0.90 x the constant-mu ratio (thesis: 0.71)", _case_tyre),
)

