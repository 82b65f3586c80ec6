"""Nominal contact figures shared by the MuJoCo model and the uncertain inputs (one source,
no import circle between them)."""

#: Stiffness of the pad under a fingertip, N/m: the project's FEM (docs/fem.md, Fig. 6.3c) at
#: p0 = 1.1 kPa under 0.5 N on a 10 mm disc, interpolated between 0.96 and 1.42 kPa.
PAD_TIP_STIFFNESS_N_M = 114.0
#: Friction of the rigid fingertips on objects, -: a hard thermoplastic (polycarbonate 0.52,
#: Shackelford and Alexander, CRC Materials Science and Engineering Handbook, 2001, Table 399).
FINGERTIP_FRICTION = 0.5
