(G90 OD turning: diameters 42, 34, 26, 18 over Z length 66, back to X50 Z5 after each)
G00 X50 Z5
G90 U-8.0 W-66.0 F400
U-16.0
U-24.0
U-32.0
G00 X100 Z100
M30
