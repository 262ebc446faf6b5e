"""Energy-optimal luffing of a level-luffing articulated jib (Loveikin et al. 2013)."""
