"""What the risk tests share: a power-law hazard λ(x) = K0 x^-K (x in m/s²), whose risk
integral has a closed form, and a point source near the site (BSSA14)."""
G = 9.80665
K0, K = 2e-4, 2.8  # λ(x) = K0 x^-K, x in m/s²
SOURCE = {"model": "BSSA14", "im": "pga", "vs30": "760 m/s",
          "levels": {"start": "0.02 g", "stop": "2.5 g", "num": 25},
          "sources": [{"kind": "point", "distance": "10 km", "depth": "8 km",
                       "recurrence": {"rate": 0.02, "m_min": 5.5, "m_max": 7.5}}]}
