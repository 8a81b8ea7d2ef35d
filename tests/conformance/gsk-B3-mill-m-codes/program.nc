O0001
(gsk B.3: the M codes of the mill: spindle, tool change, coolant, orientation, rigid tapping,)
(stops, subprogram call and return, end)
T3 M06
S1200 M03
M08
M98 P0002
M01
M04
M05
M19
M18
M09
M29 S500
M00
M30
O0002
G00 X1
M99
