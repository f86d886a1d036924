"""Plain radial bearings (Chaika–Vasylenko §2): dry, semi-fluid and fluid friction.

``tables``   the allowable parameters of Tables 2.1 and 2.2 as data, with the clearance ranges of §2.2–2.3;
``loads``    the load and sliding speed of a pair of the crank-slider over the cycle, from its kinetostatics;
``dry``      sizing (2.4)/(2.5), the checks (2.3), (2.6), (2.9) and the heat balance (2.12)/(2.13);
``film``     the Stribeck curve f(λ = μω/p_m) of Fig. 2.4 and the fluid-film friction power (2.17)–(2.19);
``report``   everything the designer shows, by output name.
"""
