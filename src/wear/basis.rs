//! What the wear law's volume stands for beside the corrosion a run computes: the split of
//! a run's loss into its mechanical and its corrosion parts (ASTM G119: total = W0 + delta
//! W_c + delta C_w).

use serde::{Deserialize, Serialize};

/// The loss Archard's k was fitted on, which decides how the groove's volume and the
/// wear-accelerated corrosion (WAC) add up.
///
/// A profilometer measures the whole loss, corrosion included, and the paper derives k from
/// such a volume (eq. 1 with Table 3's 3600 s point). Adding the WAC to a groove of that k
/// counts the corrosion twice: on `{}` the sum reads 13.24e-3 mm^3 after 3600 s against
/// the 11.72e-3 mm^3 measured (`tribosim run '{}'` on the `mechanical` basis).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VolumeBasis {
    /// k was fitted on the whole measured loss: the groove's volume is the total, and the
    /// mechanical part is the groove less the WAC.
    #[default]
    TotalLoss,
    /// k was fitted on the mechanical loss alone (a test under cathodic protection, or
    /// `tribosim calibrate archard` fitting totals with the run's corrosion): the total is
    /// the groove plus the WAC.
    Mechanical,
}

/// A run's loss split after ASTM G119.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LossSplit {
    /// The mechanical loss (the groove and Archard's wear), m^3.
    pub mechanical_m3: f64,
    /// The mechanical and the corrosion loss together, what a profilometer measures, m^3.
    pub total_m3: f64,
}

impl VolumeBasis {
    /// The loss of a groove of `groove_m3` beside `wac_m3` of corrosion. On the total-loss
    /// basis a WAC beyond the groove leaves no mechanical part (0, not negative) and the
    /// total is the WAC: the dissolved metal has left the disc, so no loss is below it. The
    /// run then warns that its corrosion exceeds the loss its k was fitted on. (Refusing
    /// instead is not possible before the run: the WAC follows the contact's area as it
    /// wears.)
    pub fn split(self, groove_m3: f64, wac_m3: f64) -> LossSplit {
        match self {
            Self::TotalLoss => LossSplit {
                mechanical_m3: (groove_m3 - wac_m3).max(0.0),
                total_m3: groove_m3.max(wac_m3),
            },
            Self::Mechanical => LossSplit {
                mechanical_m3: groove_m3,
                total_m3: groove_m3 + wac_m3,
            },
        }
    }

    /// How the total is made, for the readable summary.
    pub fn total_words(self) -> &'static str {
        match self {
            Self::TotalLoss => "the wear track, k fitted on total losses",
            Self::Mechanical => "wear + WAC",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The split with these parts, m^3.
    fn split(mechanical_m3: f64, total_m3: f64) -> LossSplit {
        LossSplit {
            mechanical_m3,
            total_m3,
        }
    }

    #[test]
    fn the_total_loss_basis_keeps_the_groove_as_the_total_and_never_goes_negative() {
        assert_eq!(VolumeBasis::TotalLoss.split(10.0, 1.5), split(8.5, 10.0));
        // A WAC beyond the groove is the whole loss: never a total below its own WAC.
        assert_eq!(VolumeBasis::TotalLoss.split(1.0, 3.0), split(0.0, 3.0));
    }

    #[test]
    fn the_mechanical_basis_adds_the_corrosion() {
        assert_eq!(VolumeBasis::Mechanical.split(10.0, 1.5), split(10.0, 11.5));
    }

    #[test]
    fn the_basis_reads_in_snake_case() {
        let basis: VolumeBasis = serde_json::from_str("\"total_loss\"").expect("valid");
        assert_eq!(basis, VolumeBasis::TotalLoss);
        assert_eq!(
            serde_json::to_string(&VolumeBasis::Mechanical).expect("serialises"),
            "\"mechanical\""
        );
    }
}
