//! Unit tests of the access policy: credentials, lockouts, kiosk allowances.

use super::*;

fn guarded() -> Access {
    let credentials = Credentials {
        operator: Secret::new("operator-credential-1"),
        dm: Secret::new("dialog-manager-cred-2"),
    };
    Access::new(AccessMode::Guarded(credentials), TrustedProxies::default())
}

const PEER: Option<IpAddr> = Some(IpAddr::V4(std::net::Ipv4Addr::new(192, 168, 1, 20)));

#[test]
fn each_role_needs_its_own_credential() {
    let access = guarded();
    assert_eq!(
        access.check(
            ClientAddress::direct(PEER),
            Needed::Operator,
            Some("operator-credential-1")
        ),
        Ok(())
    );
    assert_eq!(
        access.check(
            ClientAddress::direct(PEER),
            Needed::Dm,
            Some("dialog-manager-cred-2")
        ),
        Ok(())
    );
    assert_eq!(
        access.check(
            ClientAddress::direct(PEER),
            Needed::Either,
            Some("dialog-manager-cred-2")
        ),
        Ok(())
    );
    assert_eq!(
        access.check(
            ClientAddress::direct(PEER),
            Needed::Operator,
            Some("dialog-manager-cred-2")
        ),
        Err(Refusal::Wrong)
    );
    assert_eq!(
        access.check(ClientAddress::direct(PEER), Needed::Operator, None),
        Err(Refusal::Missing)
    );
    assert_eq!(
        access.check(ClientAddress::direct(PEER), Needed::Operator, Some("")),
        Err(Refusal::Missing)
    );
}

#[test]
fn repeated_wrong_credentials_make_only_wrong_ones_wait() {
    let access = guarded();
    let client = ClientAddress::direct(PEER);
    for _ in 1..MAX_FAILURES {
        assert_eq!(
            access.check(client, Needed::Operator, Some("guess")),
            Err(Refusal::Wrong)
        );
    }
    assert!(matches!(
        access.check(client, Needed::Operator, None),
        Err(Refusal::TooManyAttempts(_))
    ));
    assert!(matches!(
        access.check(client, Needed::Operator, Some("guess")),
        Err(Refusal::Locked(_))
    ));
    // The holder of the credential is never locked out by someone else's guesses, nor by
    // its own earlier mistakes: the right credential is compared first.
    for _ in 0..3 {
        assert_eq!(
            access.check(client, Needed::Operator, Some("operator-credential-1")),
            Ok(())
        );
        assert!(matches!(
            access.check(client, Needed::Operator, Some("guess")),
            Err(Refusal::Locked(_))
        ));
    }
    let elsewhere = Some(IpAddr::V4(std::net::Ipv4Addr::new(192, 168, 1, 21)));
    assert_eq!(
        access.check(ClientAddress::direct(elsewhere), Needed::Dm, Some("nope")),
        Err(Refusal::Wrong)
    );
}

#[test]
fn failures_counted_under_mqtt_never_reach_a_local_client() {
    let access = guarded();
    for _ in 0..(2 * MAX_FAILURES) {
        access.failed(Counted::Mqtt, Refusal::Wrong);
    }
    assert!(matches!(
        access.failed(Counted::Mqtt, Refusal::Wrong),
        Refusal::Locked(_)
    ));
    let local = ClientAddress::direct(Some(IpAddr::V4(Ipv4Addr::LOCALHOST)));
    assert_eq!(
        access.check(local, Needed::Operator, Some("guess")),
        Err(Refusal::Wrong)
    );
}

#[test]
fn an_open_server_asks_for_nothing() {
    let access = Access::new(AccessMode::Open, TrustedProxies::default());
    assert!(access.is_open());
    let local = Some(IpAddr::V4(Ipv4Addr::LOCALHOST));
    assert_eq!(
        access.check(ClientAddress::direct(local), Needed::Operator, None),
        Ok(())
    );
    // A request forwarded from elsewhere (a proxy, a tunnel) gets nothing for free.
    assert_eq!(
        access.check(ClientAddress::direct(PEER), Needed::Operator, None),
        Err(Refusal::Missing)
    );
}

#[test]
fn kiosks_at_one_address_share_one_allowance() {
    let access = guarded();
    let now = Instant::now();
    for _ in 0..5 {
        assert_eq!(
            access.kiosk_allowance(PEER, KioskAllowance::Visitor, now),
            Ok(())
        );
    }
    assert!(
        access
            .kiosk_allowance(PEER, KioskAllowance::Visitor, now)
            .is_err()
    );
    let elsewhere = Some(IpAddr::V4(Ipv4Addr::new(192, 168, 1, 99)));
    assert_eq!(
        access.kiosk_allowance(elsewhere, KioskAllowance::Visitor, now),
        Ok(())
    );
}

#[test]
fn recording_reports_have_an_allowance_of_their_own() {
    let access = guarded();
    let now = Instant::now();
    for _ in 0..10 {
        let taken = access.kiosk_allowance(PEER, KioskAllowance::Recording, now);
        assert_eq!(taken, Ok(()));
    }
    let refused = access.kiosk_allowance(PEER, KioskAllowance::Recording, now);
    assert_eq!(refused, Err(Duration::from_secs(1)));
    // The visitor's taps are untouched.
    assert_eq!(
        access.kiosk_allowance(PEER, KioskAllowance::Visitor, now),
        Ok(())
    );
}

#[test]
fn the_shells_own_reports_never_spend_the_visitors_taps() {
    let access = guarded();
    let now = Instant::now();
    for _ in 0..8 {
        assert_eq!(
            access.kiosk_allowance(PEER, KioskAllowance::Shell, now),
            Ok(())
        );
    }
    assert!(
        access
            .kiosk_allowance(PEER, KioskAllowance::Shell, now)
            .is_err()
    );
    for _ in 0..5 {
        assert_eq!(
            access.kiosk_allowance(PEER, KioskAllowance::Visitor, now),
            Ok(())
        );
    }
    assert!(
        access
            .kiosk_allowance(PEER, KioskAllowance::Visitor, now)
            .is_err()
    );
}

#[test]
fn refusal_messages_never_contain_the_token() {
    let access = guarded();
    let refusal = access
        .check(
            ClientAddress::direct(PEER),
            Needed::Operator,
            Some("my-guess-token"),
        )
        .unwrap_err();
    assert!(!refusal.message(Needed::Operator).contains("my-guess-token"));
    assert_eq!(refusal.code(), ErrorCode::Unauthorized);
}

#[test]
fn waits_are_told_in_whole_seconds_rounded_up() {
    assert_eq!(whole_seconds(Duration::from_millis(9_900)), 10);
    assert_eq!(whole_seconds(Duration::from_secs(10)), 10);
    assert_eq!(whole_seconds(Duration::from_millis(1)), 1);
    assert_eq!(whole_seconds(Duration::ZERO), 1);
}

#[test]
fn loopback_addresses_are_recognised() {
    assert!(is_loopback(Some("127.0.0.1".parse().unwrap())));
    assert!(is_loopback(Some("::1".parse().unwrap())));
    assert!(is_loopback(Some("::ffff:127.0.0.1".parse().unwrap())));
    assert!(!is_loopback(Some("192.168.1.2".parse().unwrap())));
    assert!(!is_loopback(None));
}
