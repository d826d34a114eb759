//! The scripted input of `sdfc view --script`: drags, pans, zooms and keys, one step per
//! finished picture (for tests and recordings).

use crate::cli::Error;
use std::collections::VecDeque;

/// One step of `--script`.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// `drag DX DY`: an orbit drag of so many pixels.
    Drag(f64, f64),
    /// `pan DX DY`: a pan drag.
    Pan(f64, f64),
    /// `zoom N`: wheel steps (positive: closer).
    Zoom(f64),
    /// `key K`: a key press.
    Key(String),
    /// `orbit S`: a steady drag for S seconds, a turn every frame as a held mouse gives, after
    /// which the viewer says how many frames it showed (its own frame rate while moving).
    Orbit(f64),
}

/// Parses `--script`: steps separated by `;`.
pub fn parse_script(text: &str) -> Result<VecDeque<Step>, Error> {
    text.split(';')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            let words: Vec<&str> = s.split_whitespace().collect();
            let num = |i: usize| -> Result<f64, Error> {
                words
                    .get(i)
                    .and_then(|w| w.parse().ok())
                    .ok_or_else(|| format!("error: `--script`: `{s}` needs a number").into())
            };
            match words[0] {
                "drag" => Ok(Step::Drag(num(1)?, num(2)?)),
                "pan" => Ok(Step::Pan(num(1)?, num(2)?)),
                "zoom" => Ok(Step::Zoom(num(1)?)),
                "key" if words.len() == 2 => Ok(Step::Key(words[1].to_string())),
                "orbit" => match num(1)? {
                    s if s > 0.0 && s <= 600.0 => Ok(Step::Orbit(s)),
                    _ => Err(format!("error: `--script`: `{s}`: orbit for 0 to 600 seconds").into()),
                },
                _ => Err(format!(
                    "error: `--script`: `{s}` is not `drag DX DY`, `pan DX DY`, `zoom N`, `orbit S` or `key K`"
                )
                .into()),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scripts_parse_or_say_what_is_wrong() {
        let s = parse_script("drag 180 0; zoom 2 ;key t;  pan -3 4.5; orbit 2.5").unwrap();
        assert_eq!(
            Vec::from(s),
            [
                Step::Drag(180.0, 0.0),
                Step::Zoom(2.0),
                Step::Key("t".into()),
                Step::Pan(-3.0, 4.5),
                Step::Orbit(2.5)
            ]
        );
        assert!(
            parse_script("drag 1")
                .unwrap_err()
                .to_string()
                .contains("`drag 1` needs a number")
        );
        assert!(
            parse_script("orbit 0")
                .unwrap_err()
                .to_string()
                .contains("orbit for 0 to 600 seconds")
        );
        assert!(
            parse_script("spin 3")
                .unwrap_err()
                .to_string()
                .contains("is not `drag DX DY`")
        );
    }
}
