O9010 (spec L5296-5315: a three-stage search on input 13; without the runtime the signal comes at each end point)
G98
G31 UA-400 F300 L13
G31 UA-20 K13
G01 UA-3
G31 UA30 F50 L13 R100
IF[#100==0]
#3000=1(NOT DETECTED)
ENDIF
G50 A0
M30
