0
O0121 (NAME)
G00 X1 (move) Z2 ; trailing
G01 X2 F100 // slash comment
(only a comment)

N30 g00 x3 z-1
m30
