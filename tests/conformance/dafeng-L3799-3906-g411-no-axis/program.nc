O1000 (G41.1 on a channel without the rotary axis of param 5550)
G00 X0 Z0
G41.1
G01 Z10 F300
M30
