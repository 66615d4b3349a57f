//! Unit tests of the site settings: credentials never shown, and how they are compared.

use super::*;

#[test]
fn a_credential_never_shows_in_debug_output() {
    let token = Credential::new("s3cret-s3cret-s3cret").expect("strong enough");
    assert_eq!(format!("{token:?}"), "Credential(***)");
    let access = AccessSettings {
        operator_token: Some(token.clone()),
        dm_token: None,
    };
    assert!(!format!("{access:?}").contains("s3cret"));
    assert_eq!(token.expose(), "s3cret-s3cret-s3cret");
}

#[test]
fn a_credential_has_16_visible_ascii_characters_or_more() {
    assert_eq!(Credential::new("short"), Err(WeakCredential::TooShort(5)));
    assert!(Credential::new("a".repeat(16)).is_ok());
    assert_eq!(
        Credential::new("a".repeat(15)),
        Err(WeakCredential::TooShort(15))
    );
    for bad in [
        "sixteen chars ok!",
        "tab\tinside-the-token",
        "caf\u{e9}-caf\u{e9}-caf\u{e9}-x",
    ] {
        assert_eq!(
            Credential::new(bad),
            Err(WeakCredential::NotPlain),
            "{bad:?}"
        );
    }
}

#[test]
fn credentials_compare_by_content() {
    let a = Credential::new("0123456789abcdef").expect("ok");
    assert_eq!(a, Credential::new("0123456789abcdef").expect("ok"));
    assert_ne!(a, Credential::new("0123456789abcdeF").expect("ok"));
    assert_ne!(a, Credential::new("0123456789abcdef0").expect("ok"));
}
