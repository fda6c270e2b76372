; t008_short_lead: the shortest lead
teeth    = 8
steps    = even
diameter = 40000
lead     = 50000
hand     = right
noise    = 0.02
blur     = 1.5
image    = 768
seed     = 163
