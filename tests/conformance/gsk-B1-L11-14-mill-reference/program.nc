(gsk B.1 L11-14: G28 through the intermediate point to the reference point, G29 back through)
(it to the point given, G30 to the 2nd reference point, G27 checks the reference point)
G90 G54 G00 X10 Y20 Z30
G28 X40 Y50
G29 X5 Y6
G30 Z35
G91 G28 Z0
G90 G27 X100
M30
