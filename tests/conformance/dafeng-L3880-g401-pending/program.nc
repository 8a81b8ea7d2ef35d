O1002 (spec L3880, L3889: after G40.1 A stands where the control's last move leaves it. Under)
(G42 that move is still in the look-ahead, so programming A there is an alarm: 1121)
T0101
G00 X20 Z30
G41.1
G42 G01 Z20 F300
G01 X0
G40.1
G00 A0
G40 G00 X40
M30
