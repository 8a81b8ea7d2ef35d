(gsk B.4 item 8a / D3-6 in the mill: a vacant variable removes its word, 0 does not)
G00 X5 Y5
G90 X100 Y#1
#1=0
G90 X100 Y#1
#2=#10
IF [#2 NE #0] #3000=1 (#2=#10 KEEPS VACANT)
#3=#10*5
IF [#3 NE 0] #3000=2 (VACANT TIMES 5 IS 0)
G00 X#1 Y#11
M30
