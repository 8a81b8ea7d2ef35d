O1000 (gsk A.6.29: G92.1 F-1.5, a left-hand thread, two starts; the modal block keeps the hand)
G00 X40 Z5
M14
G92.1 X38 Z-20 F-1.5 L2 S300
X37.4
G00 X60
M30
