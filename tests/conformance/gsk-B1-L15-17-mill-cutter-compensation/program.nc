(gsk B.1 L15-17: G41 D1 around a 40 mm square clockwise: the cutter's centre 5 outside every)
(side, arcs about the outside corners; G40 leaves it; G42 D1 the other way round cuts inside)
G90 G00 X0 Y-20 Z0
G41 D1 G01 X0 Y0 F200
Y40
X40
Y0
X0
G40 G00 X0 Y-20
G42 D1 G01 X0 Y0
Y40
X40
Y0
X0
G40 G00 X0 Y-20
M30
