O1000 (gsk A.6.41 L1279-1312: G92 P1 repairs; the modal blocks after it repair without P1, rule 4)
G00 X30 Z5
G92 X19.2 Z-20 F2 P1
X18.6
X18.4
G92 X18.4 Z-20 F2
G00 X40 Z50
M30
