O1000 (electronic cam: the spec's example, dafeng L3067-3085, on cam_lathe.yaml)
G00 X55 Z0 (the safe point)
M98 P8000 (load the lift table #100-#459)
G51.8 P100 L360 (X follows the table from S1's angle)
M03 S100
G01 U-1 F30 (grinding feed)
G04 X1 (spark out)
G00 U10 (retract)
G50.8 (the lift is taken off X)
M30
O8000 (the lift table: 360 points, one per degree, a 1 mm bump)
#1=0
WHILE[#1 LT 360] DO1
#[100+#1]=0.5*[1-COS[#1]]
#1=#1+1
END1
M99
