//! Traditional Japanese colours and the palettes a dyer would choose
//! from them (docs/SPEC.md §1.6; issue "kimono craft", item 5).
//!
//! **Where the values come from.** Every colour is one of the traditional
//! colour names (和色名) of JIS Z 8102:2001 *Names of non-luminous object
//! colours*, whose table of customary names gives each a Munsell notation
//! (hue value/chroma). The sRGB values here were computed from those
//! notations, not taken from any colour list: the Munsell renotation
//! (xyY under CIE illuminant C, as colour-science 0.4.7's
//! `munsell_colour_to_xyY` interpolates it), adapted to D65 by the Bradford
//! transform, encoded as sRGB and rounded; the four colours that lie
//! beyond sRGB (yamabuki, ukon, asagi, nando) are clipped channel by
//! channel. `tools/palettes.py` does the conversion and prints this table.
//! A printed sample differs with paper, ink and light: these are previews,
//! as every fill moyo writes is.
//!
//! **Names.** A colour is named in Hepburn romaji, lower case, with `-iro`
//! (色) where Japanese says it (`ai-iro`, 藍色); the name without `-iro`
//! (`ai`) and the kanji (`藍色`) are accepted too.
//!
//! **Palettes.** Five colours each, in roles the templates rely on, so one
//! line (`palette = "…"`) recolours a design: `@1` the main flowers, `@2`
//! the ground (backgrounds, the waves and clouds), `@3` leaves, `@4` the
//! second flowers, `@5` an accent.

use super::Color;

/// One traditional colour of JIS Z 8102:2001 (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Traditional {
    /// Romaji name, e.g. `ai-iro`.
    pub name: &'static str,
    /// The name in kanji (and kana), e.g. `藍色`.
    pub kanji: &'static str,
    /// Its Munsell notation in JIS Z 8102:2001.
    pub munsell: &'static str,
    /// The sRGB colour computed from the notation.
    pub color: Color,
}

/// The traditional colours moyo knows, from warm to cool to grey.
pub const TRADITIONAL: [Traditional; 54] = [
    Traditional {
        name: "sakura-iro",
        kanji: "桜色",
        munsell: "10RP 9/2.5",
        color: Color::rgb(245, 221, 223),
    },
    Traditional {
        name: "kobai-iro",
        kanji: "紅梅色",
        munsell: "2.5R 6.5/7.5",
        color: Color::rgb(219, 138, 141),
    },
    Traditional {
        name: "akane-iro",
        kanji: "茜色",
        munsell: "4R 3.5/11",
        color: Color::rgb(159, 32, 56),
    },
    Traditional {
        name: "shu-iro",
        kanji: "朱色",
        munsell: "6R 5.5/14",
        color: Color::rgb(234, 80, 78),
    },
    Traditional {
        name: "karakurenai",
        kanji: "韓紅花",
        munsell: "1.5R 5.5/13",
        color: Color::rgb(226, 85, 110),
    },
    Traditional {
        name: "suou",
        kanji: "蘇芳",
        munsell: "4R 4/7",
        color: Color::rgb(149, 73, 76),
    },
    Traditional {
        name: "tobi-iro",
        kanji: "鳶色",
        munsell: "7.5R 3.5/5",
        color: Color::rgb(125, 68, 62),
    },
    Traditional {
        name: "bengara-iro",
        kanji: "弁柄色",
        munsell: "8R 3.5/7",
        color: Color::rgb(136, 60, 52),
    },
    Traditional {
        name: "ebicha",
        kanji: "海老茶",
        munsell: "8R 3/4.5",
        color: Color::rgb(108, 57, 52),
    },
    Traditional {
        name: "toki-iro",
        kanji: "鴇色",
        munsell: "7RP 7.5/8",
        color: Color::rgb(247, 163, 184),
    },
    Traditional {
        name: "botan-iro",
        kanji: "牡丹色",
        munsell: "3RP 5/14",
        color: Color::rgb(200, 72, 150),
    },
    Traditional {
        name: "ouni",
        kanji: "黄丹",
        munsell: "10R 6/12",
        color: Color::rgb(233, 111, 66),
    },
    Traditional {
        name: "hiwada-iro",
        kanji: "桧皮色",
        munsell: "1YR 4.3/4",
        color: Color::rgb(138, 93, 79),
    },
    Traditional {
        name: "taisha",
        kanji: "代赭",
        munsell: "2.5YR 5/8.5",
        color: Color::rgb(182, 100, 57),
    },
    Traditional {
        name: "koji-iro",
        kanji: "柑子色",
        munsell: "5.5YR 7.5/9",
        color: Color::rgb(249, 169, 99),
    },
    Traditional {
        name: "kohaku-iro",
        kanji: "琥珀色",
        munsell: "8YR 5.5/6.5",
        color: Color::rgb(176, 124, 68),
    },
    Traditional {
        name: "kuchiba-iro",
        kanji: "朽葉色",
        munsell: "10YR 5/2",
        color: Color::rgb(135, 119, 100),
    },
    Traditional {
        name: "yamabuki-iro",
        kanji: "山吹色",
        munsell: "10YR 7.5/13",
        color: Color::rgb(247, 173, 0),
    },
    Traditional {
        name: "odo-iro",
        kanji: "黄土色",
        munsell: "10YR 6/7.5",
        color: Color::rgb(188, 139, 62),
    },
    Traditional {
        name: "karashi-iro",
        kanji: "芥子色",
        munsell: "3Y 7/6",
        color: Color::rgb(201, 170, 98),
    },
    Traditional {
        name: "ukon-iro",
        kanji: "鬱金色",
        munsell: "2Y 7.5/12",
        color: Color::rgb(236, 178, 0),
    },
    Traditional {
        name: "kariyasu-iro",
        kanji: "刈安色",
        munsell: "7Y 8.5/7",
        color: Color::rgb(231, 215, 113),
    },
    Traditional {
        name: "kihada-iro",
        kanji: "黄蘗色",
        munsell: "9Y 8/8",
        color: Color::rgb(213, 204, 86),
    },
    Traditional {
        name: "miru-iro",
        kanji: "海松色",
        munsell: "9.5Y 4.5/2.5",
        color: Color::rgb(113, 110, 79),
    },
    Traditional {
        name: "hiwa-iro",
        kanji: "鶸色",
        munsell: "1GY 7.5/8",
        color: Color::rgb(192, 193, 76),
    },
    Traditional {
        name: "uguisu-iro",
        kanji: "鶯色",
        munsell: "1GY 4.5/3.5",
        color: Color::rgb(110, 112, 67),
    },
    Traditional {
        name: "moegi",
        kanji: "萌黄",
        munsell: "4GY 6.5/9",
        color: Color::rgb(148, 171, 41),
    },
    Traditional {
        name: "matsuba-iro",
        kanji: "松葉色",
        munsell: "7.5GY 5/4",
        color: Color::rgb(104, 129, 88),
    },
    Traditional {
        name: "tokiwa-iro",
        kanji: "常磐色",
        munsell: "3G 4.5/7",
        color: Color::rgb(29, 124, 80),
    },
    Traditional {
        name: "rokusho-iro",
        kanji: "緑青色",
        munsell: "4G 5/4",
        color: Color::rgb(86, 131, 106),
    },
    Traditional {
        name: "wakatake-iro",
        kanji: "若竹色",
        munsell: "6G 6/7.5",
        color: Color::rgb(57, 165, 126),
    },
    Traditional {
        name: "seiji-iro",
        kanji: "青磁色",
        munsell: "7.5G 6.5/4",
        color: Color::rgb(117, 172, 150),
    },
    Traditional {
        name: "tetsu-iro",
        kanji: "鉄色",
        munsell: "2.5BG 2.5/2.5",
        color: Color::rgb(38, 65, 61),
    },
    Traditional {
        name: "asagi-iro",
        kanji: "浅葱色",
        munsell: "2.5B 5/8",
        color: Color::rgb(0, 136, 158),
    },
    Traditional {
        name: "shinbashi-iro",
        kanji: "新橋色",
        munsell: "2.5B 6.5/5.5",
        color: Color::rgb(90, 172, 184),
    },
    Traditional {
        name: "nando-iro",
        kanji: "納戸色",
        munsell: "4B 4/6",
        color: Color::rgb(0, 106, 127),
    },
    Traditional {
        name: "kamenozoki",
        kanji: "甕覗き",
        munsell: "4.5B 7/4",
        color: Color::rgb(131, 182, 193),
    },
    Traditional {
        name: "sora-iro",
        kanji: "空色",
        munsell: "9B 7.5/5.5",
        color: Color::rgb(137, 195, 221),
    },
    Traditional {
        name: "hanada-iro",
        kanji: "縹色",
        munsell: "3PB 4/7.5",
        color: Color::rgb(44, 100, 146),
    },
    Traditional {
        name: "ai-iro",
        kanji: "藍色",
        munsell: "2PB 3/5",
        color: Color::rgb(35, 75, 106),
    },
    Traditional {
        name: "ruri-iro",
        kanji: "瑠璃色",
        munsell: "6PB 3.5/11",
        color: Color::rgb(31, 81, 158),
    },
    Traditional {
        name: "kakitsubata-iro",
        kanji: "杜若色",
        munsell: "7PB 4/10",
        color: Color::rgb(70, 92, 163),
    },
    Traditional {
        name: "gunjo-iro",
        kanji: "群青色",
        munsell: "7.5PB 3.5/11",
        color: Color::rgb(63, 76, 157),
    },
    Traditional {
        name: "kikyo-iro",
        kanji: "桔梗色",
        munsell: "9PB 3.5/13",
        color: Color::rgb(81, 68, 166),
    },
    Traditional {
        name: "fuji-iro",
        kanji: "藤色",
        munsell: "10PB 6.5/6.5",
        color: Color::rgb(159, 155, 202),
    },
    Traditional {
        name: "edo-murasaki",
        kanji: "江戸紫",
        munsell: "3P 3.5/7",
        color: Color::rgb(99, 72, 124),
    },
    Traditional {
        name: "kodai-murasaki",
        kanji: "古代紫",
        munsell: "7.5P 4/6",
        color: Color::rgb(120, 83, 123),
    },
    Traditional {
        name: "nasukon",
        kanji: "茄子紺",
        munsell: "7.5P 2.5/2.5",
        color: Color::rgb(71, 54, 73),
    },
    Traditional {
        name: "ayame-iro",
        kanji: "菖蒲色",
        munsell: "10P 6/10",
        color: Color::rgb(197, 122, 180),
    },
    Traditional {
        name: "kinari-iro",
        kanji: "生成り色",
        munsell: "10YR 9/1",
        color: Color::rgb(235, 226, 213),
    },
    Traditional {
        name: "ginnezu",
        kanji: "銀鼠",
        munsell: "N 6.5",
        color: Color::rgb(160, 160, 160),
    },
    Traditional {
        name: "chanezu",
        kanji: "茶鼠",
        munsell: "5YR 6/1",
        color: Color::rgb(157, 145, 139),
    },
    Traditional {
        name: "rikyunezu",
        kanji: "利休鼠",
        munsell: "2.5G 5/1",
        color: Color::rgb(114, 124, 117),
    },
    Traditional {
        name: "susutake-iro",
        kanji: "煤竹色",
        munsell: "9.5YR 3.5/1.5",
        color: Color::rgb(95, 81, 69),
    },
];

/// A named palette: five traditional colours in the roles `@1`–`@5`
/// (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Palette {
    /// Its name in descriptions, e.g. `kaga-gosai`.
    pub name: &'static str,
    /// What it is.
    pub about: &'static str,
    /// Romaji names of its colours, `@1` first.
    pub colors: [&'static str; 5],
}

/// The palettes; the first is the one a description without `palette`
/// uses.
pub const PALETTES: [Palette; 5] = [
    Palette {
        name: "kaga-gosai",
        about: "the five colours of Kaga-yūzen (加賀五彩): enji crimson, indigo, \
                grass green, ancient purple and yellow ochre; JIS has no enji or \
                kusa, so akane (madder red) and matsuba (pine needle) stand in",
        colors: [
            "akane-iro",
            "ai-iro",
            "matsuba-iro",
            "kodai-murasaki",
            "odo-iro",
        ],
    },
    Palette {
        name: "kyo",
        about: "Kyō-yūzen brights: vermilion, light blue-green, sprout green, \
                ibis pink and kerria yellow",
        colors: ["shu-iro", "asagi-iro", "moegi", "toki-iro", "yamabuki-iro"],
    },
    Palette {
        name: "edo",
        about: "Edo's subdued iki: Edo purple on indigo, Rikyū grey-green, \
                storeroom blue and soot-bamboo brown",
        colors: [
            "edo-murasaki",
            "ai-iro",
            "rikyunezu",
            "nando-iro",
            "susutake-iro",
        ],
    },
    Palette {
        name: "haru",
        about: "spring: red plum, sky blue, sprout green, cherry blossom and \
                kerria yellow",
        colors: [
            "kobai-iro",
            "sora-iro",
            "moegi",
            "sakura-iro",
            "yamabuki-iro",
        ],
    },
    Palette {
        name: "aki",
        about: "autumn: yellow-red (ōni), maroon, fallen-leaf brown, madder \
                red and turmeric yellow",
        colors: ["ouni", "ebicha", "kuchiba-iro", "akane-iro", "ukon-iro"],
    },
];

/// The traditional colour named `name` (romaji with or without `-iro`, or
/// kanji; romaji in any case).
pub fn traditional(name: &str) -> Option<&'static Traditional> {
    let name = name.trim();
    TRADITIONAL.iter().find(|t| {
        t.name.eq_ignore_ascii_case(name)
            || t.kanji == name
            || t.name
                .strip_suffix("-iro")
                .is_some_and(|bare| bare.eq_ignore_ascii_case(name))
    })
}

/// The palette named `name`.
pub fn palette(name: &str) -> Option<&'static Palette> {
    PALETTES.iter().find(|p| p.name == name)
}

impl Palette {
    /// The colour of slot `n` (1–5).
    pub fn slot(&self, n: usize) -> Option<Color> {
        let name = self.colors.get(n.checked_sub(1)?)?;
        traditional(name).map(|t| t.color)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_palette_names_five_known_colours() {
        for p in PALETTES {
            for n in 1..=5 {
                assert!(p.slot(n).is_some(), "{} @{n}", p.name);
            }
            assert_eq!(p.slot(0), None);
            assert_eq!(p.slot(6), None);
        }
    }

    #[test]
    fn names_are_unique_and_found_every_way() {
        for (i, t) in TRADITIONAL.iter().enumerate() {
            assert!(TRADITIONAL[..i]
                .iter()
                .all(|u| u.name != t.name && u.kanji != t.kanji));
            assert_eq!(traditional(t.name), Some(t));
            assert_eq!(traditional(t.kanji), Some(t));
            assert_eq!(traditional(&t.name.to_uppercase()), Some(t));
        }
        assert_eq!(traditional("ai").map(|t| t.kanji), Some("藍色"));
        assert_eq!(traditional("indigo-ish"), None);
    }

    /// The values follow their Munsell notations: higher value is lighter,
    /// greys (N, chroma 0–1.5) are nearly neutral.
    #[test]
    fn colours_follow_their_munsell_values() {
        let lightness =
            |c: Color| 0.2126 * f64::from(c.r) + 0.7152 * f64::from(c.g) + 0.0722 * f64::from(c.b);
        let value = |t: &Traditional| -> f64 {
            let v = t.munsell.rsplit(' ').next().unwrap();
            v.split('/').next().unwrap().parse().unwrap()
        };
        for a in TRADITIONAL {
            for b in TRADITIONAL {
                if value(&a) >= value(&b) + 2.0 {
                    assert!(
                        lightness(a.color) > lightness(b.color),
                        "{} vs {}",
                        a.name,
                        b.name
                    );
                }
            }
        }
        let g = traditional("ginnezu").unwrap().color;
        assert!(g.r == g.g && g.g == g.b, "{g}");
    }
}
