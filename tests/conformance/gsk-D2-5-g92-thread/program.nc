(lead 2, then I8 = 3.175 mm; rapid out, rapid back)
G00 X60 Z5
G92 X48 Z-30 F2
G92 X48 Z-30 I8
M30
