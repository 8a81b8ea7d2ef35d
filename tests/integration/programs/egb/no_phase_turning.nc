O3 (G81.4 without R while the hob turns: nothing is matched, so the hob must stand)
G00 X30 Z5 C0
M03 S300
G81.4 T20 L1
G01 X20 F300
M30
