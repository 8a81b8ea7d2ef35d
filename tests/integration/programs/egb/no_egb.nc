O1 (G81.4 on cam_lathe.yaml, whose channel has no gear box)
G00 X55 Z0
M03 S100
G81.4 T20 L1 R0
G01 U-1 F30
M30
