//! The language features of the server over the protocol, in this process, on a workspace folder
//! written from `fixtures/lsp/workspace.txt` (cursor markers `«name»`): indexing with progress,
//! definition (a label, a PROC in a file that is not open), references, highlights, rename and its
//! refusals, completion with snippets, signature help of CYCLE81, semantic tokens decoded with the
//! legend, hover documentation, and the cross-file diagnostics published with the analysis's and
//! updated when another file changes on disk.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{apply_text_edits, file_uri, temp_folder, TestClient};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::path::PathBuf;

/// The fixture written to a folder: file texts and the markers' positions (file, line, UTF-16 column).
struct Workspace {
    folder: PathBuf,
    texts: HashMap<String, String>,
    marks: HashMap<String, (String, u32, u32)>,
}

impl Workspace {
    fn write(name: &str) -> Workspace {
        let fixture = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/fixtures/lsp/workspace.txt"
        ))
        .unwrap();
        let folder = temp_folder(name);
        let mut texts: HashMap<String, String> = HashMap::new();
        let mut marks = HashMap::new();
        let mut current: Option<String> = None;
        for line in fixture.lines() {
            if let Some(file) = line.strip_prefix(";;; FILE ") {
                current = Some(file.trim().to_string());
                texts.insert(file.trim().to_string(), String::new());
                continue;
            }
            let Some(file) = &current else { continue };
            let text = texts.get_mut(file).unwrap();
            let line_number = text.matches('\n').count() as u32;
            let mut clean = String::new();
            let mut rest = line;
            while let Some(start) = rest.find('«') {
                clean.push_str(&rest[..start]);
                let end = rest.find('»').expect("a closed marker");
                let mark = &rest[start + '«'.len_utf8()..end];
                let column = clean.encode_utf16().count() as u32;
                marks.insert(mark.to_string(), (file.clone(), line_number, column));
                rest = &rest[end + '»'.len_utf8()..];
            }
            clean.push_str(rest);
            text.push_str(&clean);
            text.push('\n');
        }
        for (file, text) in &texts {
            std::fs::write(folder.join(file), text).unwrap();
        }
        Workspace {
            folder,
            texts,
            marks,
        }
    }

    fn uri(&self, file: &str) -> String {
        file_uri(&self.folder.join(file))
    }

    /// `{"textDocument", "position"}` at a marker.
    fn at(&self, mark: &str) -> Value {
        let (file, line, character) = &self.marks[mark];
        json!({"textDocument": {"uri": self.uri(file)}, "position": {"line": line, "character": character}})
    }

    /// A location as (file name, line, start character).
    fn mark(&self, mark: &str) -> (String, u64, u64) {
        let (file, line, character) = &self.marks[mark];
        (file.clone(), *line as u64, *character as u64)
    }
}

/// A location answer as (file name, line, start character).
fn place(location: &Value) -> (String, u64, u64) {
    let uri = location["uri"].as_str().unwrap();
    let file = uri.rsplit('/').next().unwrap().to_string();
    (
        file,
        location["range"]["start"]["line"].as_u64().unwrap(),
        location["range"]["start"]["character"].as_u64().unwrap(),
    )
}

/// A server with the workspace folder, MAIN.MPF open, the indexing finished; returns the progress
/// notifications seen. The client renames files that workspace edits ask it to.
async fn start(workspace: &Workspace) -> (TestClient, Vec<Value>) {
    start_with_edits(
        workspace,
        json!({"documentChanges": true, "resourceOperations": ["rename"]}),
    )
    .await
}

/// [`start`] with the client's `workspaceEdit` capabilities.
async fn start_with_edits(
    workspace: &Workspace,
    workspace_edit: Value,
) -> (TestClient, Vec<Value>) {
    let mut client = TestClient::in_process();
    let folder_uri = file_uri(&workspace.folder);
    client
        .request(
            "initialize",
            json!({
                "processId": null,
                "rootUri": folder_uri,
                "workspaceFolders": [{"uri": folder_uri, "name": "fixture"}],
                "capabilities": {
                    "window": {"workDoneProgress": true},
                    "workspace": {
                        "didChangeWatchedFiles": {"dynamicRegistration": true},
                        "workspaceEdit": workspace_edit
                    },
                    "textDocument": {"completion": {"completionItem": {"snippetSupport": true}}}
                }
            }),
        )
        .await
        .expect("initialize succeeds");
    client.notify("initialized", json!({})).await;
    let mut progress = Vec::new();
    loop {
        let params = client.notification("$/progress", |_| true).await;
        let done = params["value"]["kind"] == "end";
        progress.push(params);
        if done {
            break;
        }
    }
    let main = workspace.uri("MAIN.MPF");
    client.open(&main, 1, &workspace.texts["MAIN.MPF"]).await;
    (client, progress)
}

fn codes(diagnostics: &Value) -> Vec<String> {
    diagnostics
        .as_array()
        .unwrap()
        .iter()
        .map(|diagnostic| diagnostic["code"].as_str().unwrap().to_string())
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_workspace_is_indexed_with_progress_and_watched() {
    let workspace = Workspace::write("indexing");
    let (mut client, progress) = start(&workspace).await;
    let request = client
        .server_request("window/workDoneProgress/create")
        .await;
    let token = &request["params"]["token"];
    assert!(progress.iter().all(|params| &params["token"] == token));
    assert_eq!(progress.first().unwrap()["value"]["kind"], "begin");
    assert!(progress
        .iter()
        .any(|params| params["value"]["kind"] == "report"));
    assert_eq!(
        progress.last().unwrap()["value"]["message"],
        "2 files indexed"
    );
    let registration = client.server_request("client/registerCapability").await;
    let registered = &registration["params"]["registrations"][0];
    assert_eq!(registered["method"], "workspace/didChangeWatchedFiles");
    let patterns: Vec<&str> = registered["registerOptions"]["watchers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|watcher| watcher["globPattern"].as_str().unwrap())
        .collect();
    assert_eq!(
        patterns,
        ["**/*.{mpf,spf,def,MPF,SPF,DEF}", "**/sinumerik.toml"]
    );

    // Workspace symbols find the PROC of the file that is not open.
    let symbols = client
        .request("workspace/symbol", json!({"query": "part"}))
        .await
        .unwrap();
    let found: Vec<(String, (String, u64, u64))> = symbols
        .as_array()
        .unwrap()
        .iter()
        .map(|symbol| {
            (
                symbol["name"].as_str().unwrap().to_string(),
                place(&symbol["location"]),
            )
        })
        .collect();
    assert!(
        found.contains(&("PART2".to_string(), workspace.mark("procName"))),
        "{found:?}"
    );
    assert!(
        found.contains(&("END_PART".to_string(), workspace.mark("labelDefinition"))),
        "{found:?}"
    );

    // A changed sinumerik.toml can change how every file reads (its axes): the files on disk are
    // indexed again.
    std::fs::write(workspace.folder.join("sinumerik.toml"), "").unwrap();
    client
        .notify(
            "workspace/didChangeWatchedFiles",
            json!({"changes": [{"uri": workspace.uri("sinumerik.toml"), "type": 1}]}),
        )
        .await;
    let again = tokio::time::timeout(
        std::time::Duration::from_secs(30),
        client.notification("$/progress", |params| {
            &params["token"] != token && params["value"]["kind"] == "end"
        }),
    )
    .await
    .expect("the workspace is indexed again");
    assert_eq!(again["value"]["message"], "2 files indexed");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn definition_references_and_highlights() {
    let workspace = Workspace::write("navigation");
    let (mut client, _) = start(&workspace).await;

    let answer = client
        .request("textDocument/definition", workspace.at("jumpName"))
        .await
        .unwrap();
    let targets: Vec<_> = answer.as_array().unwrap().iter().map(place).collect();
    assert_eq!(targets, vec![workspace.mark("labelDefinition")]);

    // A call goes to the PROC header of the other file, which is not open.
    let answer = client
        .request("textDocument/definition", workspace.at("call"))
        .await
        .unwrap();
    let targets: Vec<_> = answer.as_array().unwrap().iter().map(place).collect();
    assert_eq!(targets, vec![workspace.mark("procName")]);

    let mut params = workspace.at("labelDefinition");
    params["context"] = json!({"includeDeclaration": true});
    let answer = client
        .request("textDocument/references", params.clone())
        .await
        .unwrap();
    let mut found: Vec<_> = answer.as_array().unwrap().iter().map(place).collect();
    found.sort();
    assert_eq!(
        found,
        vec![workspace.mark("jump"), workspace.mark("labelDefinition")]
    );
    params["context"] = json!({"includeDeclaration": false});
    let answer = client
        .request("textDocument/references", params)
        .await
        .unwrap();
    let found: Vec<_> = answer.as_array().unwrap().iter().map(place).collect();
    assert_eq!(found, vec![workspace.mark("jump")]);

    // References of the PROC from its call: the header and the call.
    let mut params = workspace.at("call");
    params["context"] = json!({"includeDeclaration": true});
    let answer = client
        .request("textDocument/references", params)
        .await
        .unwrap();
    let mut found: Vec<_> = answer.as_array().unwrap().iter().map(place).collect();
    found.sort();
    assert_eq!(
        found,
        vec![workspace.mark("callsite"), workspace.mark("procName")]
    );

    let answer = client
        .request("textDocument/documentHighlight", workspace.at("jumpName"))
        .await
        .unwrap();
    let mut lines: Vec<(u64, u64)> = answer
        .as_array()
        .unwrap()
        .iter()
        .map(|highlight| {
            (
                highlight["range"]["start"]["line"].as_u64().unwrap(),
                highlight["range"]["start"]["character"].as_u64().unwrap(),
            )
        })
        .collect();
    lines.sort();
    let (_, jump_line, jump_column) = workspace.mark("jump");
    let (_, label_line, label_column) = workspace.mark("labelDefinition");
    assert_eq!(
        lines,
        vec![(jump_line, jump_column), (label_line, label_column)]
    );
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn rename_edits_every_occurrence_and_refuses_bad_names() {
    let workspace = Workspace::write("rename");
    let (mut client, _) = start(&workspace).await;
    let main = workspace.uri("MAIN.MPF");

    let prepared = client
        .request("textDocument/prepareRename", workspace.at("jumpName"))
        .await
        .unwrap();
    assert_eq!(prepared["placeholder"], "END_PART");

    let mut params = workspace.at("labelDefinition");
    params["newName"] = json!("finish");
    let edit = client.request("textDocument/rename", params).await.unwrap();
    let changes = edit["documentChanges"].as_array().unwrap();
    assert_eq!(changes.len(), 1);
    assert_eq!(changes[0]["textDocument"]["uri"], main.as_str());
    assert_eq!(changes[0]["textDocument"]["version"], 1);
    let renamed = apply_text_edits(
        &workspace.texts["MAIN.MPF"],
        changes[0]["edits"].as_array().unwrap(),
    );
    assert!(renamed.contains("N40 GOTOF FINISH\n"), "{renamed}");
    assert!(renamed.contains("\nFINISH:\n"), "{renamed}");
    assert!(!renamed.contains("END_PART"), "{renamed}");

    // The PROC is renamed in its own file (not open: no version) and at the call, and its file
    // after them: the control finds the program by its file name.
    let mut params = workspace.at("call");
    params["newName"] = json!("PART3");
    let edit = client.request("textDocument/rename", params).await.unwrap();
    let changes = edit["documentChanges"].as_array().unwrap();
    let (renames, text_edits): (Vec<&Value>, Vec<&Value>) = changes
        .iter()
        .partition(|change| change["kind"] == "rename");
    let mut edited: Vec<(String, Value)> = text_edits
        .iter()
        .map(|change| {
            let uri = change["textDocument"]["uri"].as_str().unwrap();
            (
                uri.rsplit('/').next().unwrap().to_string(),
                change["textDocument"]["version"].clone(),
            )
        })
        .collect();
    edited.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(
        edited,
        vec![
            ("MAIN.MPF".to_string(), json!(1)),
            ("PART2.SPF".to_string(), Value::Null)
        ]
    );
    assert_eq!(renames.len(), 1, "{edit}");
    assert_eq!(renames[0]["oldUri"], workspace.uri("PART2.SPF").as_str());
    assert_eq!(renames[0]["newUri"], workspace.uri("PART3.SPF").as_str());
    assert_eq!(renames[0]["options"]["overwrite"], false);
    assert_eq!(
        changes.last(),
        Some(renames[0]),
        "the file is renamed after its edits"
    );

    // A file of the new name that the index does not know yet is not overwritten.
    std::fs::write(workspace.folder.join("PART3.SPF"), "M17\n").unwrap();
    let message = refused_rename(&mut client, &workspace, "call", "PART3").await;
    assert!(
        message.contains("PART3.SPF") && message.contains("exists"),
        "{message}"
    );
    std::fs::remove_file(workspace.folder.join("PART3.SPF")).unwrap();

    for (new_name, reason) in [("G1", "G"), ("IF", "keyword"), ("X", "axis")] {
        let message = refused_rename(&mut client, &workspace, "labelDefinition", new_name).await;
        assert!(
            message.to_lowercase().contains(&reason.to_lowercase()),
            "{new_name}: {message}"
        );
    }
    // A name another symbol has: R1 is an R parameter, PART2 a program.
    let message = refused_rename(&mut client, &workspace, "labelDefinition", "PART2").await;
    assert!(message.contains("PART2"), "{message}");
    client.shutdown().await;
}

/// Renames the symbol at `mark` to `new_name`, which the server must refuse as a request that
/// cannot be done (RequestFailed); returns the reason it gives.
async fn refused_rename(
    client: &mut TestClient,
    workspace: &Workspace,
    mark: &str,
    new_name: &str,
) -> String {
    let mut params = workspace.at(mark);
    params["newName"] = json!(new_name);
    let error = client
        .request("textDocument/rename", params)
        .await
        .expect_err("the rename is refused");
    assert_eq!(error["code"], -32803, "{error}");
    error["message"].as_str().unwrap().to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_program_is_renamed_only_by_a_client_that_can_rename_its_file() {
    let workspace = Workspace::write("rename_without_files");
    let (mut client, _) = start_with_edits(&workspace, json!({"documentChanges": true})).await;
    // Renaming the calls alone would break them.
    let message = refused_rename(&mut client, &workspace, "call", "PART3").await;
    assert!(message.contains("PART2.SPF"), "{message}");
    // Other names are renamed as before.
    let mut params = workspace.at("labelDefinition");
    params["newName"] = json!("FINISH");
    let edit = client.request("textDocument/rename", params).await.unwrap();
    assert_eq!(edit["documentChanges"].as_array().unwrap().len(), 1);
    client.shutdown().await;

    // Neovim 0.7 names the resource operations but not `documentChanges`: the file is renamed, after
    // the edits of MAIN.MPF and PART2.SPF.
    let (mut client, _) = start_with_edits(
        &workspace,
        json!({"resourceOperations": ["rename", "create", "delete"]}),
    )
    .await;
    let mut params = workspace.at("call");
    params["newName"] = json!("PART3");
    let edit = client.request("textDocument/rename", params).await.unwrap();
    let changes = edit["documentChanges"].as_array().unwrap();
    assert_eq!(changes.len(), 3, "{edit}");
    assert_eq!(changes[2]["kind"], "rename", "{edit}");
    assert_eq!(changes[2]["newUri"], workspace.uri("PART3.SPF").as_str());
    client.shutdown().await;
}

async fn complete_at(client: &mut TestClient, uri: &str, line: usize, character: u32) -> Value {
    client
        .request(
            "textDocument/completion",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}),
        )
        .await
        .expect("completion succeeds")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn completion_signature_help_and_hover_documentation() {
    let workspace = Workspace::write("completion");
    let (mut client, _) = start(&workspace).await;
    let main = workspace.uri("MAIN.MPF");
    // A new line "N80 CYC" at the end: completion offers the cycles with a snippet.
    let line_count = workspace.texts["MAIN.MPF"].matches('\n').count();
    client
        .change(
            &main,
            2,
            json!([{"range": {"start": {"line": line_count, "character": 0}, "end": {"line": line_count, "character": 0}}, "text": "N80 CYC"}]),
        )
        .await;
    let answer = complete_at(&mut client, &main, line_count, 7).await;
    let items = answer.as_array().unwrap();
    let cycle81 = items
        .iter()
        .find(|item| item["label"] == "CYCLE81")
        .expect("CYCLE81 is offered");
    assert_eq!(cycle81["insertTextFormat"], 2, "{cycle81}");
    assert!(
        cycle81["insertText"]
            .as_str()
            .unwrap()
            .starts_with("CYCLE81(${1:RTP}"),
        "{cycle81}"
    );
    assert!(items
        .iter()
        .all(|item| item["label"].as_str().unwrap().starts_with("CYC")));

    // G functions come with their group.
    client
        .change(
            &main,
            3,
            json!([{"range": {"start": {"line": line_count, "character": 4}, "end": {"line": line_count, "character": 7}}, "text": "G6"}]),
        )
        .await;
    let answer = complete_at(&mut client, &main, line_count, 6).await;
    let g64 = answer
        .as_array()
        .unwrap()
        .iter()
        .find(|item| item["label"] == "G64")
        .expect("G64 is offered");
    assert!(
        g64["detail"].as_str().unwrap().contains("10"),
        "G64 is in group 10: {g64}"
    );

    let help = client
        .request("textDocument/signatureHelp", workspace.at("cycleArgument"))
        .await
        .unwrap();
    let signature = &help["signatures"][0];
    assert!(
        signature["label"]
            .as_str()
            .unwrap()
            .starts_with("CYCLE81(RTP, RFP, SDIS, DP, DPR"),
        "{signature}"
    );
    assert_eq!(help["activeParameter"], 3);
    let label = signature["label"].as_str().unwrap();
    let offsets = &signature["parameters"][3]["label"];
    let (start, end) = (
        offsets[0].as_u64().unwrap() as usize,
        offsets[1].as_u64().unwrap() as usize,
    );
    assert_eq!(&label[start..end], "DP");

    // Hover: the PROC's doc comment on the call, the resolution on an axis word.
    let (_, line, character) = workspace.mark("call");
    let hover = client.hover(&main, line as u32, character as u32).await;
    assert!(hover.contains("Roughs the contour"), "{hover}");
    let (_, line, character) = workspace.mark("axis");
    let hover = client.hover(&main, line as u32, character as u32).await;
    assert!(hover.contains("**20.000** mm"), "{hover}");
    let (_, line, character) = workspace.mark("cycleArgument");
    let hover = client
        .hover(&main, line as u32, character as u32 - 12)
        .await;
    assert!(hover.contains("CYCLE81"), "{hover}");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn semantic_tokens_decode_to_the_words_kinds() {
    let workspace = Workspace::write("semantic");
    let mut client = TestClient::in_process();
    let result = client.initialize(json!({}), Value::Null).await;
    let legend = &result["capabilities"]["semanticTokensProvider"]["legend"];
    let types: Vec<&str> = legend["tokenTypes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|kind| kind.as_str().unwrap())
        .collect();
    let modifiers: Vec<&str> = legend["tokenModifiers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|kind| kind.as_str().unwrap())
        .collect();
    let uri = workspace.uri("MAIN.MPF");
    let text = &workspace.texts["MAIN.MPF"];
    client.open(&uri, 1, text).await;
    let decode = |answer: &Value| -> Vec<(u64, String, String, Vec<String>)> {
        let data: Vec<u64> = answer["data"]
            .as_array()
            .unwrap()
            .iter()
            .map(|number| number.as_u64().unwrap())
            .collect();
        let lines: Vec<&str> = text.lines().collect();
        let (mut line, mut start) = (0, 0);
        data.chunks(5)
            .map(|token| {
                if token[0] > 0 {
                    line += token[0];
                    start = token[1];
                } else {
                    start += token[1];
                }
                let word = &lines[line as usize][start as usize..(start + token[2]) as usize];
                let set: Vec<String> = (0..modifiers.len())
                    .filter(|bit| token[4] & (1 << bit) != 0)
                    .map(|bit| modifiers[bit].to_string())
                    .collect();
                (
                    line,
                    word.to_string(),
                    types[token[3] as usize].to_string(),
                    set,
                )
            })
            .collect()
    };
    let full = client
        .request(
            "textDocument/semanticTokens/full",
            json!({"textDocument": {"uri": uri}}),
        )
        .await
        .unwrap();
    let tokens = decode(&full);
    let has = |word: &str, kind: &str| {
        tokens
            .iter()
            .any(|(_, found, found_kind, _)| found == word && found_kind == kind)
    };
    assert!(has("N10", "blockNumber"), "{tokens:?}");
    assert!(has("G0", "gcode"), "{tokens:?}");
    assert!(has("R1", "rParameter"), "{tokens:?}");
    assert!(
        has("CYCLE81", "subprogram") || has("CYCLE81", "function"),
        "{tokens:?}"
    );
    let g0 = tokens.iter().find(|(_, word, _, _)| word == "G0").unwrap();
    assert!(g0.3.contains(&"motion".to_string()), "{g0:?}");
    let definition_line = workspace.mark("labelDefinition").1;
    let label = tokens
        .iter()
        .find(|(line, word, kind, _)| {
            word == "END_PART" && kind == "label" && *line == definition_line
        })
        .expect("the label definition is a label");
    assert!(label.3.contains(&"declaration".to_string()), "{label:?}");

    // A range gives the tokens of its lines only, with the same kinds.
    let range = client
        .request(
            "textDocument/semanticTokens/range",
            json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 1, "character": 0}, "end": {"line": 1, "character": 99}}}),
        )
        .await
        .unwrap();
    let mut ranged = decode(&range);
    // Decoding starts at line 0: the first token's delta is its line.
    ranged.retain(|(line, _, _, _)| *line == 1);
    let expected: Vec<_> = tokens
        .iter()
        .filter(|(line, ..)| *line == 1)
        .cloned()
        .collect();
    assert!(!expected.is_empty());
    assert_eq!(ranged, expected);
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cross_file_findings_are_published_with_the_analysis_and_follow_other_files() {
    let workspace = Workspace::write("diagnostics");
    let (mut client, _) = start(&workspace).await;
    let main = workspace.uri("MAIN.MPF");
    // W302: three arguments for the two parameters of PART2, with W304 (MAIN_START does not
    // exist) and the analysis's S130 (the unclosed CYCLE81 call), in one publication.
    let published = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == main.as_str()
                && codes(&params["diagnostics"]).contains(&"W302".to_string())
        })
        .await;
    assert_eq!(published["version"], 1);
    let found = codes(&published["diagnostics"]);
    assert!(found.contains(&"W304".to_string()), "{found:?}");
    assert!(found.contains(&"S130".to_string()), "{found:?}");
    let w302 = published["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .find(|diagnostic| diagnostic["code"] == "W302")
        .unwrap();
    assert_eq!(w302["range"]["start"]["line"], workspace.mark("call").1);

    // A line inserted above moves the findings with their blocks at once, in the publication of
    // the new version.
    client
        .change(
            &main,
            2,
            json!([{"range": {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 0}}, "text": "; new first line\n"}]),
        )
        .await;
    let diagnostics = client.diagnostics(&main, 2).await;
    let w302 = diagnostics
        .iter()
        .find(|diagnostic| diagnostic["code"] == "W302")
        .expect("W302 is still published");
    assert_eq!(w302["range"]["start"]["line"], workspace.mark("call").1 + 1);

    // PART2 gets a third parameter on disk: the finding goes.
    std::fs::write(
        workspace.folder.join("PART2.SPF"),
        "PROC PART2(REAL A, REAL B, REAL C)\nG1 X=A F=B\nM17\n",
    )
    .unwrap();
    client
        .notify(
            "workspace/didChangeWatchedFiles",
            json!({"changes": [{"uri": workspace.uri("PART2.SPF"), "type": 2}]}),
        )
        .await;
    let published = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == main.as_str()
                && params["version"] == 2
                && !codes(&params["diagnostics"]).contains(&"W302".to_string())
        })
        .await;
    let found = codes(&published["diagnostics"]);
    assert!(found.contains(&"W304".to_string()), "{found:?}");
    assert!(found.contains(&"S130".to_string()), "{found:?}");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_findings_of_running_a_program_are_published_as_check_reports_them() {
    // MAIN.MPF calls WAIT, which waits in a loop that never ends: the run reports E401 at the call,
    // with the subprogram found in the workspace, as `check` does.
    let folder = temp_folder("execution-findings");
    let main_text = "N10 G90 G0 X0\nN20 WAIT\nN30 G0 X10\nM30\n";
    std::fs::write(folder.join("MAIN.MPF"), main_text).unwrap();
    std::fs::write(
        folder.join("WAIT.SPF"),
        "PROC WAIT\nN10 LOOP\nN20 MSG(\"waiting\")\nN30 ENDLOOP\nN40 RET\n",
    )
    .unwrap();
    let mut texts = HashMap::new();
    texts.insert("MAIN.MPF".to_string(), main_text.to_string());
    let workspace = Workspace {
        folder,
        texts,
        marks: HashMap::new(),
    };
    let (mut client, _) = start(&workspace).await;
    let main = workspace.uri("MAIN.MPF");
    let published = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == main.as_str()
                && codes(&params["diagnostics"]).contains(&"E401".to_string())
        })
        .await;
    let e401 = published["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .find(|diagnostic| diagnostic["code"] == "E401")
        .unwrap();
    assert_eq!(e401["range"]["start"]["line"], 1);
    assert!(
        e401["message"].as_str().unwrap().starts_with("in WAIT"),
        "{e401}"
    );
    let (code, stdout, _) = {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
            .args(["check", "--format", "json"])
            .arg(workspace.folder.join("MAIN.MPF"))
            .output()
            .unwrap();
        (
            output.status.code(),
            String::from_utf8(output.stdout).unwrap(),
            output.stderr,
        )
    };
    assert_eq!(code, Some(0));
    let checked: Value = serde_json::from_str(&stdout).unwrap();
    let from_check: Vec<(u64, String)> = checked
        .as_array()
        .unwrap()
        .iter()
        .filter(|item| item["code"].as_str().unwrap().starts_with('E'))
        .map(|item| {
            (
                item["line"].as_u64().unwrap() - 1,
                item["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(
        from_check,
        vec![(1, e401["message"].as_str().unwrap().to_string())]
    );
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_findings_of_the_cycle_models_are_published_as_check_reports_them() {
    // T128 (reference §19.3): HOLES1 without a modal call is E421, HOLES2 with NUM = 0 is E422; a
    // CYCLE81 with planes on the wrong side is E420. The server and `check` report them alike.
    let folder = temp_folder("cycle-findings");
    let main_text = "N10 G17 G90 G0 X0 Y0 Z50\nN20 HOLES1(20, 10, 0, 10, 15, 4)\nN30 HOLES2(0, 0, 30, 0, 90, 0)\nN40 CYCLE81(-10, 0, 1, -5)\nM30\n";
    std::fs::write(folder.join("MAIN.MPF"), main_text).unwrap();
    let mut texts = HashMap::new();
    texts.insert("MAIN.MPF".to_string(), main_text.to_string());
    let workspace = Workspace {
        folder,
        texts,
        marks: HashMap::new(),
    };
    let (mut client, _) = start(&workspace).await;
    let main = workspace.uri("MAIN.MPF");
    let published = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == main.as_str()
                && codes(&params["diagnostics"]).contains(&"E422".to_string())
        })
        .await;
    let mut from_server: Vec<(u64, String, String)> = published["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|diagnostic| diagnostic["code"].as_str().unwrap().starts_with('E'))
        .map(|diagnostic| {
            (
                diagnostic["range"]["start"]["line"].as_u64().unwrap(),
                diagnostic["code"].as_str().unwrap().to_string(),
                diagnostic["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    from_server.sort();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(["check", "--format", "json"])
        .arg(workspace.folder.join("MAIN.MPF"))
        .output()
        .unwrap();
    let checked: Value = serde_json::from_slice(&output.stdout).unwrap();
    let mut from_check: Vec<(u64, String, String)> = checked
        .as_array()
        .unwrap()
        .iter()
        .filter(|item| item["code"].as_str().unwrap().starts_with('E'))
        .map(|item| {
            (
                item["line"].as_u64().unwrap() - 1,
                item["code"].as_str().unwrap().to_string(),
                item["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    from_check.sort();
    let found: Vec<(u64, &str)> = from_check
        .iter()
        .map(|(line, code, _)| (*line, code.as_str()))
        .collect();
    assert_eq!(found, vec![(1, "E421"), (2, "E422"), (3, "E420")]);
    assert_eq!(from_server, from_check);
    client.shutdown().await;
}
