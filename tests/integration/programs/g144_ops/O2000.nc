O2000 (CT-G144-03, channel 2: the operation the caller's Q selects)
CH2
IF[#17==10] GOTO 10
IF[#17==20] GOTO 20
IF[#17==30] GOTO 30
M30
N10 G01 X10 F600 (operation 1)
G145
G00 X0
M99
N20 G01 X20 F600 (operation 2)
G145
G00 X0
M99
N30 G01 X30 F600 (operation 3)
G145
G00 X0
M99
