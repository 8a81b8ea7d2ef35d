O1000 (CT-G144-02, channel 1: spec dafeng 3.4 example 2)
CH1
G144 N2 P2000 H0 (start channel 2, no wait)
G144 N3 P3000 H0 (start channel 3, no wait)
G01 X20 Z-5 F600
G04.1 P1 Q123 (all channels done)
M30
