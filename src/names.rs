//! Names in error messages, bounded: a list of names shows a few and counts the rest, and a
//! name read from a file is cut to a readable length, so that no error line grows with the
//! input (an OBJ of 100,000 groups, a group name of a megabyte).

/// The names a list shows before it counts the rest.
pub const LISTED_NAMES: usize = 8;

/// The characters of a name an error shows before it cuts it with "…".
pub const NAME_CHARS: usize = 64;

/// `name` as an error shows it: whole up to [`NAME_CHARS`] characters, otherwise cut there
/// and ended with "…".
pub fn shown(name: &str) -> String {
    match name.char_indices().nth(NAME_CHARS) {
        None => name.to_string(),
        Some((end, _)) => format!("{}…", &name[..end]),
    }
}

/// Up to [`LISTED_NAMES`] of `names`, each [`shown`], joined by ", ", then "… and N more"
/// for the rest; "none" for no name.
pub fn listed<'a>(names: impl ExactSizeIterator<Item = &'a str>) -> String {
    let total = names.len();
    if total == 0 {
        return "none".to_string();
    }
    let mut list: Vec<String> = names.take(LISTED_NAMES).map(shown).collect();
    if total > LISTED_NAMES {
        list.push(format!("… and {} more", thousands(total - LISTED_NAMES)));
    }
    list.join(", ")
}

/// `n` with a comma between groups of three digits: 99,990.
fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, digit) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(digit);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_list_is_shown_whole() {
        assert_eq!(listed(["a", "b"].into_iter()), "a, b");
        assert_eq!(listed(std::iter::empty()), "none");
    }

    #[test]
    fn a_long_list_names_a_few_and_counts_the_rest() {
        let names: Vec<String> = (0..100_000).map(|i| format!("g{i}")).collect();
        let line = listed(names.iter().map(String::as_str));
        assert_eq!(line, "g0, g1, g2, g3, g4, g5, g6, g7, … and 99,992 more");
    }

    #[test]
    fn a_long_name_is_cut_on_a_character_boundary() {
        let name = "é".repeat(1_000_000);
        let line = listed([name.as_str()].into_iter());
        assert_eq!(line.chars().count(), NAME_CHARS + 1);
        assert!(line.ends_with('…'));
        assert_eq!(shown("short"), "short");
    }

    #[test]
    fn thousands_are_grouped() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(1_234_567), "1,234,567");
    }
}
