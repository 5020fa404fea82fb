#!/usr/bin/env python3
"""Prints the table of src/scene/traditional.rs from the Munsell notations
that JIS Z 8102:2001 gives the traditional colour names.

Munsell renotation (xyY, illuminant C) by colour-science, Bradford
adaptation to D65, sRGB, clipped per channel where a colour lies beyond
sRGB. Run with colour-science 0.4.7 and SciPy installed:

    python3 -m venv /tmp/cs && /tmp/cs/bin/pip install colour-science==0.4.7 scipy
    /tmp/cs/bin/python tools/palettes.py
"""

import warnings

import colour
import numpy as np

# (romaji, kanji, Munsell notation in JIS Z 8102:2001)
COLOURS = [
    ("sakura-iro", "桜色", "10RP 9/2.5"),
    ("kobai-iro", "紅梅色", "2.5R 6.5/7.5"),
    ("akane-iro", "茜色", "4R 3.5/11"),
    ("shu-iro", "朱色", "6R 5.5/14"),
    ("karakurenai", "韓紅花", "1.5R 5.5/13"),
    ("suou", "蘇芳", "4R 4/7"),
    ("tobi-iro", "鳶色", "7.5R 3.5/5"),
    ("bengara-iro", "弁柄色", "8R 3.5/7"),
    ("ebicha", "海老茶", "8R 3/4.5"),
    ("toki-iro", "鴇色", "7RP 7.5/8"),
    ("botan-iro", "牡丹色", "3RP 5/14"),
    ("ouni", "黄丹", "10R 6/12"),
    ("hiwada-iro", "桧皮色", "1YR 4.3/4"),
    ("taisha", "代赭", "2.5YR 5/8.5"),
    ("koji-iro", "柑子色", "5.5YR 7.5/9"),
    ("kohaku-iro", "琥珀色", "8YR 5.5/6.5"),
    ("kuchiba-iro", "朽葉色", "10YR 5/2"),
    ("yamabuki-iro", "山吹色", "10YR 7.5/13"),
    ("odo-iro", "黄土色", "10YR 6/7.5"),
    ("karashi-iro", "芥子色", "3Y 7/6"),
    ("ukon-iro", "鬱金色", "2Y 7.5/12"),
    ("kariyasu-iro", "刈安色", "7Y 8.5/7"),
    ("kihada-iro", "黄蘗色", "9Y 8/8"),
    ("miru-iro", "海松色", "9.5Y 4.5/2.5"),
    ("hiwa-iro", "鶸色", "1GY 7.5/8"),
    ("uguisu-iro", "鶯色", "1GY 4.5/3.5"),
    ("moegi", "萌黄", "4GY 6.5/9"),
    ("matsuba-iro", "松葉色", "7.5GY 5/4"),
    ("tokiwa-iro", "常磐色", "3G 4.5/7"),
    ("rokusho-iro", "緑青色", "4G 5/4"),
    ("wakatake-iro", "若竹色", "6G 6/7.5"),
    ("seiji-iro", "青磁色", "7.5G 6.5/4"),
    ("tetsu-iro", "鉄色", "2.5BG 2.5/2.5"),
    ("asagi-iro", "浅葱色", "2.5B 5/8"),
    ("shinbashi-iro", "新橋色", "2.5B 6.5/5.5"),
    ("nando-iro", "納戸色", "4B 4/6"),
    ("kamenozoki", "甕覗き", "4.5B 7/4"),
    ("sora-iro", "空色", "9B 7.5/5.5"),
    ("hanada-iro", "縹色", "3PB 4/7.5"),
    ("ai-iro", "藍色", "2PB 3/5"),
    ("ruri-iro", "瑠璃色", "6PB 3.5/11"),
    ("kakitsubata-iro", "杜若色", "7PB 4/10"),
    ("gunjo-iro", "群青色", "7.5PB 3.5/11"),
    ("kikyo-iro", "桔梗色", "9PB 3.5/13"),
    ("fuji-iro", "藤色", "10PB 6.5/6.5"),
    ("edo-murasaki", "江戸紫", "3P 3.5/7"),
    ("kodai-murasaki", "古代紫", "7.5P 4/6"),
    ("nasukon", "茄子紺", "7.5P 2.5/2.5"),
    ("ayame-iro", "菖蒲色", "10P 6/10"),
    ("kinari-iro", "生成り色", "10YR 9/1"),
    ("ginnezu", "銀鼠", "N 6.5"),
    ("chanezu", "茶鼠", "5YR 6/1"),
    ("rikyunezu", "利休鼠", "2.5G 5/1"),
    ("susutake-iro", "煤竹色", "9.5YR 3.5/1.5"),
]

ILLUMINANT_C = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["C"]


def srgb(munsell):
    xyy = colour.munsell_colour_to_xyY(munsell.replace("N ", "N"))
    rgb = colour.XYZ_to_sRGB(
        colour.xyY_to_XYZ(xyy),
        illuminant=ILLUMINANT_C,
        chromatic_adaptation_transform="Bradford",
    )
    return [int(round(c * 255)) for c in np.clip(rgb, 0.0, 1.0)]


def main():
    warnings.filterwarnings("ignore")
    for name, kanji, munsell in COLOURS:
        r, g, b = srgb(munsell)
        print(
            f'    Traditional {{ name: "{name}", kanji: "{kanji}", '
            f'munsell: "{munsell}", color: Color::rgb({r}, {g}, {b}) }},'
        )


if __name__ == "__main__":
    main()
