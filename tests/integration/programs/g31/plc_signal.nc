O3101 (G31 P2: Z probes down to a face that the PLC's skip signal 2, G0014.1, sees at Z-12.5)
G98 G00 X20 Z0
G31 W-50 F600 P2 R100
#101=#5062
G00 W1
G00 Z[#101+#100*2]
M30
