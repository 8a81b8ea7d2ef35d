O3100 (G31: Z probes down to a face that Z1's touch probe meets at Z-12.5)
G98 G00 X20 Z0
G31 W-50 F600 L13 R100
#101=#5062
G00 W1
G00 Z[#101+#100*2]
M30
