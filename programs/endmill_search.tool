; Tool model for endmill_search.kp (contracts.md section 5): the 4-flute
; variable-pitch end mill Ø20 as it really is -- the program does not know
; these numbers, it measures them with G10 M10.
teeth    = 4
steps    = 85, 95, 85, 95   ; variable pitch against chatter, degrees
diameter = 20000            ; µm
lead     = 90000            ; µm: helix 34.9° at Ø20
hand     = right
noise    = 0.02
blur     = 1.2
image    = 768
seed     = 7
