//! The balls of the library. A scene reads a ball's E and nu; its density and hardness are
//! listed for the reader (the ball is elastic and does not wear in the model).

use super::{BallMaterial, BallMaterialName, missing, read};

const ALUMINA: BallMaterial = BallMaterial {
    name: BallMaterialName::Alumina,
    label: "Alumina, sintered, >= 99.5% Al2O3",
    youngs_modulus_gpa: read(416.0, "nist-srd150", "+- 30 at 20 C"),
    poisson_ratio: read(
        0.23,
        "nist-srd150",
        "derived from NIST's E and bulk modulus K: (3K - E) / 6K",
    ),
    density_g_cm3: read(3.984, "nist-srd150", ""),
    hardness: ("HV 2000 (99.9% Al2O3)", "kientec"),
};

const ZIRCONIA: BallMaterial = BallMaterial {
    name: BallMaterialName::Zirconia,
    label: "Zirconia, 3Y-TZP",
    youngs_modulus_gpa: read(205.0, "zirconia-compilation", ""),
    poisson_ratio: read(0.30, "zirconia-compilation", ""),
    density_g_cm3: read(6.05, "zirconia-compilation", ""),
    hardness: ("HV30 1350", "zirconia-compilation"),
};

const SILICON_NITRIDE: BallMaterial = BallMaterial {
    name: BallMaterialName::SiliconNitride,
    label: "Silicon nitride, sintered and HIPed",
    youngs_modulus_gpa: read(306.0, "nist-nt164", ""),
    poisson_ratio: missing(
        "no value for a bearing-grade ball was read; MakeItFrom gives 0.24-0.27 across \
         Si3N4 grades",
    ),
    density_g_cm3: read(3.20, "lily-si3n4", "at least"),
    hardness: ("H 18.5 GPa", "nist-nt164"),
};

const STEEL_100CR6: BallMaterial = BallMaterial {
    name: BallMaterialName::Steel100Cr6,
    label: "100Cr6 / AISI 52100 bearing steel, through hardened",
    youngs_modulus_gpa: read(203.0, "ball-52100", "29.5e6 psi"),
    poisson_ratio: missing("no maker's value was read; distributors give 0.27-0.30 for 52100"),
    density_g_cm3: read(7.83, "ball-52100", "0.283 lb/in^3"),
    hardness: ("HRC 60-67", "ball-52100"),
};

const TUNGSTEN_CARBIDE: BallMaterial = BallMaterial {
    name: BallMaterialName::TungstenCarbide,
    label: "WC-Co cemented carbide (the source does not state the cobalt content)",
    youngs_modulus_gpa: read(630.0, "makeitfrom-wc", "92e6 psi"),
    poisson_ratio: read(0.24, "makeitfrom-wc", ""),
    density_g_cm3: read(15.0, "makeitfrom-wc", "two digits"),
    hardness: ("Knoop 1670", "makeitfrom-wc"),
};

/// Every ball of the library, in the order of `docs/materials.md`.
pub const BALLS: [BallMaterial; 5] = [
    ALUMINA,
    ZIRCONIA,
    SILICON_NITRIDE,
    STEEL_100CR6,
    TUNGSTEN_CARBIDE,
];
