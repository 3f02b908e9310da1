//! Where the materials library's values were read: one entry per document, cited by key
//! from each value ([`super::Property::source`]) and listed with its address in
//! `docs/materials.md`.

use serde::Serialize;

/// A document the library quotes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Reference {
    /// What a value cites.
    pub key: &'static str,
    /// The document, as a reader would look it up.
    pub citation: &'static str,
    /// Where it was read (a stored copy's address where the original was not reachable).
    pub address: &'static str,
    /// Primary (the maker's sheet, a standard, a paper or an evaluated database) or
    /// secondary (an aggregator or a distributor's copy).
    pub primary: bool,
}

/// Every document the library cites, in the order of `docs/materials.md`.
pub const REFERENCES: &[Reference] = &[
    Reference {
        key: "dalmau2018",
        citation: "A. Dalmau, A. Roda Buch, A. Rovira, J. Navarro-Laboulais, A. Igual Munoz, \
                   Wear 394-395 (2018) 166-175: Section 2.1 (H 2473 +- 110 MPa by HV1, E 205 \
                   +- 6 by ultrasound, nu 0.28), Table 2 (3% NaCl, Ag/AgCl 3 M KCl), Table 3, \
                   Section 5.1 (i_a 10 mA/cm^2)",
        address: "https://doi.org/10.1016/j.wear.2017.10.015",
        primary: true,
    },
    Reference {
        key: "ak-316l",
        citation: "AK Steel, 316/316L Product Data Sheet 316/316L-S-08-01-07, typical room \
                   temperature properties (Type 316L: 0.2% YS 42 ksi)",
        address: "https://it.scribd.com/document/40215823/316-316L-Data-Sheet",
        primary: true,
    },
    Reference {
        key: "astm-g102",
        citation: "ASTM G102-89 (2015), Calculation of Corrosion Rates and Related \
                   Information from Electrochemical Measurements, Table X1.2 (UNS S31600)",
        address: "https://www.document-center.com/standards/show/ASTM-G102",
        primary: true,
    },
    Reference {
        key: "ak-304",
        citation: "AK Steel, 304/304L Product Data Sheet 304/304L-S-8-01-07, typical \
                   properties (Type 304: 0.2% YS 42 ksi, HRB 82)",
        address: "https://pdfslide.net/documents/ak-steel304-304lsheet.html",
        primary: true,
    },
    Reference {
        key: "matweb-304",
        citation: "MatWeb, AISI Type 304 Stainless Steel (E 193-200 GPa, nu 0.29, HV 129 \
                   converted from HRB 70)",
        address: "https://www.scribd.com/document/416534641/304-Stainless-Steel-pdf",
        primary: false,
    },
    Reference {
        key: "matweb-ti64",
        citation: "MatWeb MTP644, Titanium Ti-6Al-4V (Grade 5), annealed bar, data from \
                   Allvac (E 114 GPa as the mean of tension and compression, nu 0.33, 0.2% \
                   YS 830 MPa)",
        address: "http://asm.matweb.com/search/SpecificMaterial.asp?bassnum=MTP644",
        primary: false,
    },
    Reference {
        key: "materials2021-ti64",
        citation: "Materials 14(3) (2021) 658, doi:10.3390/ma14030658, Table 4, extruded rod, \
                   annealed: HV1 349 +- 3 (10 N)",
        address: "https://pmc.ncbi.nlm.nih.gov/articles/PMC7867014/table/materials-14-00658-t004",
        primary: true,
    },
    Reference {
        key: "makeitfrom-f75",
        citation: "MakeItFrom, Annealed Cast R30075 (ASTM F75 CoCrMo): E 210 GPa, nu 0.29, \
                   0.2% YS 480 MPa, 8.4 g/cm^3, composition ranges",
        address: "https://makeitfrom.com/material-properties/Annealed-Cast-R30075-Alloy",
        primary: false,
    },
    Reference {
        key: "superior-ti2",
        citation: "Superior Tube, CP Titanium Grade 2 data sheet (E 105 GPa, 0.2% YS 275 MPa \
                   minimum)",
        address: "https://www.superiortube.com/products/materials/titanium-alloys/\
                  cp-titanium-grade2-uns-r56400-wnr-37124",
        primary: true,
    },
    Reference {
        key: "matweb-ti2",
        citation: "MatWeb MTU021, Titanium Grade 2, annealed 2 h at 700 C, data from Allvac \
                   (nu 0.34, 0.2% YS 340 MPa typical, 4.51 g/cm^3)",
        address: "https://asm.matweb.com/search/SpecificMaterial.asp?bassnum=MTU021",
        primary: false,
    },
    Reference {
        key: "matweb-ti2-generic",
        citation: "MatWeb, Titanium Grade 2 (generic sheet): HV 145, load not stated",
        address: "http://www.matweb.com/search/datasheet_print.aspx?\
                  matguid=24293fd5831941ec9fa01dce994973c7",
        primary: false,
    },
    Reference {
        key: "nist-srd150",
        citation: "NIST SRD 150, Sintered Alumina, after R. G. Munro, J. Am. Ceram. Soc. 80 \
                   (1997) 1919-1928: >= 99.5% Al2O3, E 416 +- 30 GPa, bulk modulus 257 +- 50 \
                   GPa, 3.984 g/cm^3 at 20 C",
        address: "https://srdata.nist.gov/CeramicDataPortal/Pds/Scdaos",
        primary: true,
    },
    Reference {
        key: "kientec",
        citation: "Kientec, physical properties of ceramics: 99.9% Al2O3, HV 2000 (load not \
                   stated)",
        address: "http://www.kientec.com/products/ceramic-ferrules/physical-properties-ceramics/",
        primary: false,
    },
    Reference {
        key: "zirconia-compilation",
        citation: "Typical properties of various types of zirconia (compiled table), Y-TZP: E \
                   205 GPa, nu 0.3, 6.05 g/cm^3, HV30 1350",
        address: "https://www.vinayaktechnoceramics.in/zirconia.html",
        primary: false,
    },
    Reference {
        key: "nist-nt164",
        citation: "NIST SRD 138, record NT-164 (Norton/TRW sintered and HIPed Si3N4), after \
                   Graves and Hecht, UDR-TR-94-136 (1995): E 306 GPa, H 18.5 GPa",
        address: "https://srdata.nist.gov/CeramicDataPortal/Tough/Ftnt164",
        primary: true,
    },
    Reference {
        key: "lily-si3n4",
        citation: "Lily Bearing, ceramic materials and their properties: Si3N4 balls, >= 3.20 \
                   g/cm^3, HV 1400-1600, E 300-315 GPa",
        address: "https://www.lily-bearing.com/ceramic-bearings/ceramic-materials-and-their-properties/",
        primary: false,
    },
    Reference {
        key: "ball-52100",
        citation: "52100 ball maker's sheet: E 29.5e6 psi, 0.283 lb/in^3, HRC 60-67 through \
                   hardened",
        address: "https://ja.scribd.com/document/252517093/ASTM-52100-Material-Del-Tornillo-de-Potencia",
        primary: false,
    },
    Reference {
        key: "makeitfrom-wc",
        citation: "MakeItFrom, Tungsten Carbide (WC), a cemented grade whose cobalt content \
                   the page does not state: E 630 GPa, nu 0.24, Knoop 1670, 15 g/cm^3",
        address: "https://www.makeitfrom.com/material-properties/Tungsten-Carbide-WC",
        primary: false,
    },
];

/// The reference cited as `key`.
pub fn reference(key: &str) -> Option<&'static Reference> {
    REFERENCES.iter().find(|r| r.key == key)
}
