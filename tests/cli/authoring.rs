//! The authoring loop as an instructor meets it: `init` a course and build it, `check --bless`
//! a scene, errors outside a course, `derive` saying why it fails, and shell completions.
//! (`serve` is in serve.rs.)

use super::{lecture, mechbook, mechbook_in, read_tree, scratch, stderr, stdout};

#[test]
fn init_makes_a_course_that_builds_and_checks_at_once() {
    let dir = scratch("init");
    let course = dir.join("my-course");
    let out = mechbook(&["init", course.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for f in [
        "mechbook.toml",
        "README.md",
        ".gitignore",
        "lectures/lecture-1/01-book.toml",
        "lectures/lecture-1/02-problem-box.toml",
    ] {
        assert!(course.join(f).is_file(), "{f} missing");
    }
    let ignore = std::fs::read_to_string(course.join(".gitignore")).unwrap();
    assert!(ignore.contains("/site/") && ignore.contains("/.mechbook-cache/"));

    let built = mechbook_in(&course, &["build"]);
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    // One plot, said in the singular.
    assert!(
        stderr(&built).contains("built 3 pages, 1 plot and 4 handouts"),
        "{}",
        stderr(&built)
    );
    let site = read_tree(&course.join("site"));
    // The example scene, the problem sheet's pages and its Moodle quiz, and the free-body plot.
    for f in [
        "index.html",
        "book.html",
        "problem-box.html",
        "handouts/lecture-1-problems-student.html",
        "handouts/lecture-1-problems-key.html",
        "export/moodle/problem-box.xml",
    ] {
        assert!(site.contains_key(f), "{f} not built: {:?}", site.keys());
    }
    assert!(
        site.keys().any(|k| k.starts_with("plots/book-flip")),
        "no flip plot: {:?}",
        site.keys()
    );
    let page = String::from_utf8(site["book.html"].clone()).unwrap();
    assert!(
        page.contains("My rigid-body course"),
        "course title missing"
    );
    let checked = mechbook_in(&course, &["check"]);
    assert_eq!(checked.status.code(), Some(0), "{}", stdout(&checked));
    // The example's wrong formula is caught, as the scene says it is.
    assert!(
        stdout(&checked).contains("1 disagree"),
        "{}",
        stdout(&checked)
    );

    // A second init into the same folder is refused and changes nothing.
    let before = read_tree(&course);
    let again = mechbook(&["init", course.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(1));
    assert!(
        stderr(&again).contains("is not empty"),
        "{}",
        stderr(&again)
    );
    assert_eq!(read_tree(&course), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn init_refuses_a_file_and_fills_an_empty_folder() {
    let dir = scratch("init-empty");
    let file = dir.join("notes.txt");
    std::fs::write(&file, "mine").unwrap();
    let out = mechbook(&["init", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("is a file"), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let out = mechbook_in(&empty, &["init"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(empty.join("lectures/lecture-1/01-book.toml").is_file());

    // What a killed init leaves (some starter files, the last cut short) is finished by the
    // next init; a folder with anything else in it is still refused.
    let killed = dir.join("killed");
    let whole = read_tree(&empty);
    for (rel, bytes) in whole.iter().take(3) {
        let p = killed.join(rel);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(&p, bytes).unwrap();
    }
    let (last, bytes) = whole.iter().nth(3).unwrap();
    let p = killed.join(last);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
    let out = mechbook(&["init", killed.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(read_tree(&killed), whole);
    std::fs::write(killed.join("README.md"), "my own notes").unwrap();
    std::fs::remove_file(killed.join("mechbook.toml")).unwrap();
    let out = mechbook(&["init", killed.to_str().unwrap()]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "an edited file was taken for a leftover"
    );
    assert_eq!(
        std::fs::read_to_string(killed.join("README.md")).unwrap(),
        "my own notes"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn outside_a_course_the_error_says_what_to_do() {
    let dir = scratch("outside");
    for command in ["build", "check", "serve"] {
        let out = mechbook_in(&dir, &[command]);
        assert_eq!(out.status.code(), Some(1), "{command}");
        let err = stderr(&out);
        assert!(
            err.contains("no lectures/ here") && err.contains("mechbook init"),
            "{command}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The hoop scene with its `[expect]` table (and its comment) removed.
fn hoop_without_expect() -> String {
    let text = std::fs::read_to_string(lecture("06-hoop.toml")).unwrap();
    let start = text.find("\n# The results as derived").unwrap();
    let end = text.find("\n# How these notes number").unwrap();
    format!("{}{}", &text[..start], &text[end..])
}

#[test]
fn bless_records_expect_in_a_scene_without_it_and_check_then_passes() {
    let dir = scratch("bless-new");
    let scene = dir.join("hoop.toml");
    let original = hoop_without_expect();
    assert!(!original.contains("[expect]"));
    std::fs::write(&scene, &original).unwrap();
    // Unrecorded results fail, as an unrecorded claim does, each at the scene's id line.
    let out = mechbook(&["check", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stdout(&out).contains(":2: `inertia_tensor` not yet recorded (derived"),
        "{}",
        stdout(&out)
    );
    assert!(stdout(&out).contains("FAILED"), "{}", stdout(&out));
    let out = mechbook(&["check", "--bless", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let printed = stdout(&out);
    assert!(
        printed.contains(
            "[expect] inertia_tensor = [[1/2*M*R^2, 0, 0], [0, 1/2*M*R^2, 0], [0, 0, M*R^2]]"
        ),
        "{printed}"
    );
    let blessed = std::fs::read_to_string(&scene).unwrap();
    // Everything that was there is still there, in order, comments included; [expect] is new.
    assert!(
        blessed.starts_with(&original),
        "the rest of the file changed"
    );
    assert!(blessed.contains("[expect]\n"));
    // The recorded tensor is the shipped scene's, which was reviewed by hand.
    let shipped = std::fs::read_to_string(lecture("06-hoop.toml")).unwrap();
    let line = |t: &str, key: &str| {
        t.lines()
            .find(|l| l.starts_with(&format!("{key} = ")))
            .map(str::to_owned)
    };
    for key in ["inertia_tensor", "principal_moments"] {
        assert_eq!(line(&blessed, key), line(&shipped, key), "{key}");
    }
    let check = mechbook(&["check", scene.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(0), "{}", stdout(&check));
    // A record is checked: spoil it and check fails again.
    std::fs::write(
        &scene,
        blessed.replace("[0, 0, M*R^2]]\"", "[0, 0, 2*M*R^2]]\""),
    )
    .unwrap();
    assert_eq!(
        mechbook(&["check", scene.to_str().unwrap()]).status.code(),
        Some(1)
    );
    // Blessing twice changes nothing the second time.
    std::fs::write(&scene, &blessed).unwrap();
    let out = mechbook(&["check", "--bless", scene.to_str().unwrap()]);
    assert!(
        stdout(&out).contains("blessed: 0 changes"),
        "{}",
        stdout(&out)
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), blessed);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_new_claim_without_a_verdict_fails_check_until_bless_records_it() {
    let dir = scratch("bless-claim");
    let scene = dir.join("hoop.toml");
    // Two claims as an author first writes them: no `expect` yet. The hoop's polar moment is
    // M R^2 (agrees); the notes' slip of a diameter moment of M R^2 disagrees (M R^2/2).
    let claims = "\n[[claim]]\neq = \"90\"\nstatement = \"The polar moment is M R^2.\"\n\
                  quantity = \"inertia_tensor[2][2]\"\nvalue = \"M*R^2\"\n\
                  \n# A slip to catch.\n[[claim]]\neq = \"91\"\nstatement = \"A diameter moment is M R^2.\"\n\
                  quantity = \"inertia_tensor[0][0]\"\nvalue = \"M*R^2\"\n";
    let original = format!(
        "{}{claims}",
        std::fs::read_to_string(lecture("06-hoop.toml")).unwrap()
    );
    std::fs::write(&scene, &original).unwrap();
    let check = mechbook(&["check", scene.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(1));
    let report = stdout(&check);
    for (eq, verdict) in [("90", "agrees"), ("91", "disagrees")] {
        assert!(
            report.contains(&format!(
                "claim ({eq}): verdict {verdict}, not yet recorded: review it, then add expect = \"{verdict}\""
            )),
            "{report}"
        );
    }
    let out = mechbook(&["check", "--bless", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let printed = stdout(&out);
    assert!(
        printed.contains("claim (eq 90): verdict (none) -> agrees"),
        "{printed}"
    );
    assert!(
        printed.contains("claim (eq 91): verdict (none) -> disagrees"),
        "{printed}"
    );
    assert!(printed.contains("blessed: 2 changes"), "{printed}");
    let blessed = std::fs::read_to_string(&scene).unwrap();
    assert!(
        blessed.contains("value = \"M*R^2\"\nexpect = \"disagrees\"\n"),
        "{blessed}"
    );
    assert!(
        blessed.contains("\n# A slip to catch.\n[[claim]]"),
        "{blessed}"
    );
    let check = mechbook(&["check", scene.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(0), "{}", stdout(&check));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bless_updates_a_verdict_and_a_result_and_keeps_comments() {
    let dir = scratch("bless-change");
    let scene = dir.join("hoop.toml");
    let shipped = std::fs::read_to_string(lecture("06-hoop.toml")).unwrap();
    // A reviewed verdict that is now wrong, with a comment of the author's on its line, and a
    // recorded result that no longer matches.
    let edited = shipped
        .replacen(
            "expect = \"disagrees\"",
            "expect = \"agrees\"  # the author's note",
            1,
        )
        .replace(
            "principal_moments = \"[1/2*M*R^2, 1/2*M*R^2, M*R^2]\"",
            "principal_moments = \"[M*R^2, M*R^2, M*R^2]\"  # old",
        );
    std::fs::write(&scene, &edited).unwrap();
    let check = mechbook(&["check", scene.to_str().unwrap()]);
    assert_eq!(check.status.code(), Some(1));
    // A changed result names its line in [expect].
    let line = edited
        .lines()
        .position(|l| l.starts_with("principal_moments"))
        .unwrap()
        + 1;
    assert!(
        stdout(&check).contains(&format!("hoop.toml:{line}: `principal_moments` changed")),
        "{}",
        stdout(&check)
    );
    let out = mechbook(&["check", "--bless", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let printed = stdout(&out);
    assert!(
        printed.contains("claim (eq 36): verdict agrees -> disagrees"),
        "{printed}"
    );
    assert!(
        printed.contains(
            "[expect] principal_moments: [M*R^2, M*R^2, M*R^2] -> [1/2*M*R^2, 1/2*M*R^2, M*R^2]"
        ),
        "{printed}"
    );
    assert!(
        printed.contains("blessed: 2 changes in 1 of 1"),
        "{printed}"
    );
    let blessed = std::fs::read_to_string(&scene).unwrap();
    let expected = shipped
        .replacen(
            "expect = \"disagrees\"",
            "expect = \"disagrees\"  # the author's note",
            1,
        )
        .replace(
            "principal_moments = \"[1/2*M*R^2, 1/2*M*R^2, M*R^2]\"",
            "principal_moments = \"[1/2*M*R^2, 1/2*M*R^2, M*R^2]\"  # old",
        );
    assert_eq!(blessed, expected);
    assert_eq!(
        mechbook(&["check", scene.to_str().unwrap()]).status.code(),
        Some(0)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn derive_says_why_it_fails() {
    let dir = scratch("derive-why");
    let scene = dir.join("hoop.toml");
    let shipped = std::fs::read_to_string(lecture("06-hoop.toml")).unwrap();
    std::fs::write(
        &scene,
        shipped.replacen("expect = \"disagrees\"", "expect = \"agrees\"", 1),
    )
    .unwrap();
    let out = mechbook(&["derive", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.contains("scene `hoop` failed 1 check:"), "{err}");
    assert!(
        err.contains("claim (36): verdict disagrees but the scene records agrees"),
        "{err}"
    );
    assert!(err.contains("mechbook check --bless"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn completions_are_printed_for_each_shell() {
    for shell in ["bash", "zsh", "fish"] {
        let out = mechbook(&["completions", shell]);
        assert_eq!(out.status.code(), Some(0), "{shell}");
        let script = stdout(&out);
        for word in ["init", "serve", "bless", "derive"] {
            assert!(script.contains(word), "{shell}: no {word}");
        }
    }
    assert_eq!(mechbook(&["completions", "tcsh"]).status.code(), Some(2));
}

#[test]
fn bless_edits_a_crlf_file_with_a_bom_and_comments_through_a_link_keeping_every_other_byte() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("bless-bytes");
    let shipped = std::fs::read_to_string(lecture("06-hoop.toml")).unwrap();
    // A comment above each key bless will change, a verdict and a result now wrong, CRLF line
    // ends and a byte-order mark.
    let file = |verdict: &str, moments: &str| {
        let text = shipped
            .replacen(
                "expect = \"disagrees\"",
                &format!("# reviewed in week 3\nexpect = \"{verdict}\""),
                1,
            )
            .replace(
                "principal_moments = \"[1/2*M*R^2, 1/2*M*R^2, M*R^2]\"",
                &format!("# the eigenvalues, ascending\nprincipal_moments = \"{moments}\""),
            );
        assert_ne!(text, shipped);
        format!("\u{feff}{}", text.replace('\n', "\r\n")).into_bytes()
    };
    let edited = file("agrees", "[M*R^2, M*R^2, M*R^2]");
    let expected = file("disagrees", "[1/2*M*R^2, 1/2*M*R^2, M*R^2]");
    // The scene lives elsewhere, shared through a link, with mode 0640.
    let real = dir.join("shared").join("hoop.toml");
    std::fs::create_dir_all(real.parent().unwrap()).unwrap();
    std::fs::write(&real, &edited).unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
    let course = dir.join("lectures");
    std::fs::create_dir_all(&course).unwrap();
    let link = course.join("hoop.toml");
    std::os::unix::fs::symlink(&real, &link).unwrap();

    let out = mechbook(&["check", "--bless", course.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stdout(&out).contains("blessed: 2 changes"),
        "{}",
        stdout(&out)
    );
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink(),
        "the link was replaced by a copy"
    );
    assert_eq!(
        std::fs::read(&real).unwrap(),
        expected,
        "other bytes changed"
    );
    let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o7777;
    assert_eq!(mode, 0o640);
    let left: Vec<_> = std::fs::read_dir(real.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}");
    assert_eq!(
        mechbook(&["check", course.to_str().unwrap()]).status.code(),
        Some(0)
    );

    // A read-only scene is refused, and left as it was.
    std::fs::write(&real, &edited).unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o440)).unwrap();
    let out = mechbook(&["check", "--bless", course.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("is read-only"), "{}", stderr(&out));
    assert_eq!(std::fs::read(&real).unwrap(), edited);
    std::fs::remove_dir_all(&dir).unwrap();
}
