(gsk B.5.3 / D3-2: the face inclined by 3 degrees in the mill dialect; M99 added, B.6)
O0001
#[#1+1*2]=1
IF[#2 NE 1] #3000=1(#[#1+1*2] DID NOT SET #2)
G65 P9012 L1 A0 B0.1 C4 I100 J3 K0
M30
O9012
G54 G90 G00 X[#3] Y0 Z100 S500 M3
G01 Z0 F300
WHILE [#1 LE 10] DO1
#7=#1/TAN[#5]+#3
G1 Z-#1 X#7
#8=#6/2-ROUND[#6/2]
IF [#8 EQ 0] GOTO10
G1 Y0
GOTO20
N10 Y#4
N20 #1=#1+#2
#6=#6+1
END1
G0 Z100
M99
