(gsk B.1 L15-17 with normal direction control, FANUC 0i-MF G41.1, dafeng L3880: C follows the)
(cutter's offset path round the 40 mm square, turning with the arcs about the outside corners)
G90 G00 X0 Y-20 Z0
G41.1
G41 D1 G01 X0 Y0 F200
Y40
X40
Y0
X0
G40 G00 X0 Y-20
G40.1
M30
