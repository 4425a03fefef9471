//! The engine's errors in the command line's words: an option's field named as the flag that
//! sets it (`max_keys` as `--max-keys`), since the engine's errors name fields, never flags.

use sweepffd::fit::{FitError, OptionError};

/// `error` as the command line reports it.
pub fn fit_error(error: &FitError) -> String {
    match error {
        FitError::Options(option) => option_error(option),
        FitError::NoSection => "no key plane cuts the part; give an --axis that runs through it".to_string(),
        other => other.to_string(),
    }
}

/// `error`, each field it names spelled as its flag.
fn option_error(error: &OptionError) -> String {
    match *error {
        OptionError::MaxKeysBelowKeys { max_keys, keys } => {
            format!("--max-keys ({max_keys}) must be at least --keys ({keys})")
        }
        other => {
            let (text, field) = (other.to_string(), other.field());
            let rest = text.strip_prefix(field).unwrap_or(&text);
            format!("--{}{rest}", field.replace('_', "-"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_option_error_names_its_flag() {
        let cases = [
            (OptionError::TooFewKeys(1), "--keys must be at least 2, found 1"),
            (OptionError::TooFewRadii(2), "--radii must be at least 3, found 2"),
            (OptionError::TooManyRadii(10_000_000), "--radii 10000000 is over the limit of 4096 radii per key"),
            (OptionError::TooManyKeys(2000), "--keys 2000 is over the limit of 1024 keys per sweep"),
            (OptionError::TooManyMaxKeys(5000), "--max-keys 5000 is over the limit of 1024 keys per sweep"),
            (OptionError::MaxKeysBelowKeys { max_keys: 3, keys: 6 }, "--max-keys (3) must be at least --keys (6)"),
            (OptionError::Tolerance(-1.0), "--tolerance must be a positive number, found -1"),
            (OptionError::Falloff(f64::NAN), "--falloff must be a finite width of at least 0 (mesh units), found NaN"),
            (OptionError::MinLength(0.0), "--min-length must be a positive fraction of the mesh's size, found 0"),
            (OptionError::TooManyParts(331), "--max-parts 331 is over the limit of 256 sweeps per rig"),
            (
                OptionError::BeyondPart { field: "max_keys", value: 49, most: 48, vertices: 48 },
                "--max-keys 49 is more than a part of 48 vertices determines (at most 48)",
            ),
        ];
        for (error, expected) in cases {
            assert_eq!(fit_error(&FitError::Options(error)), expected);
        }
        assert!(fit_error(&FitError::NoSection).contains("--axis"));
        assert!(!FitError::NoSection.to_string().contains("--"));
    }
}
