O1003 (spec L3880 with corners L1287-1365: the chamfer is a move of its own, turned into and)
(out of; the round corner is an arc that turns A with it)
G00 X0 Z0
G42.1
G01 Z10 ,C2 F300
G01 X20 ,R3
G01 Z20
G40.1
M30
