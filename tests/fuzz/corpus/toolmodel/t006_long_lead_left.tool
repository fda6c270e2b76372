; t006_long_lead_left: the longest lead
teeth    = 6
steps    = even
diameter = 30000
lead     = 2000000
hand     = left
noise    = 0.02
blur     = 1
image    = 640
seed     = 156
