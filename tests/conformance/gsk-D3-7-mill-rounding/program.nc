(gsk B.4 item 6 / D3-7 in the mill: a variable's value is rounded to 0.001 mm: X12.346)
#1=12.3456
G00 X#1
G00 X-#1
#2=123
G00 Z#2
#3=100
G01 X[#1+#2] Y#1 F#3
M30
